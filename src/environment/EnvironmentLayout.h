#pragma once
// Where the prefiltered environment's roughness levels live on the GPU (environment/Environment.h): as RGB9E5 texels
// the shader filters by hand, in the mip levels of one texture read with texture2DLodEXT (EXT_shader_texture_lod) or
// side by side in an atlas read with texture2D; or as half floats side by side, each inside a border, which the
// hardware's bilinear filter reads in one fetch (OES_texture_half_float_linear).
namespace obscura {

enum class EnvironmentLayout { MipChain, Atlas, HalfFloatAtlas };
const char* environmentLayoutName(EnvironmentLayout layout);  // "mipchain", "atlas", "halffloat"

// Which levels the hardware's filter reads (environment/Environment.h, "Storage"): by the measured bound, or one
// storage forced (the tests and benchmarks compare both).
enum class EnvironmentFiltering { Measured, ByHand, Hardware };

}  // namespace obscura
