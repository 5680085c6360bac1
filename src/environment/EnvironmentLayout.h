#pragma once
// Where the prefiltered environment's roughness levels live on the GPU (environment/Environment.h): the mip levels of
// one texture read with texture2DLodEXT (EXT_shader_texture_lod), or side by side in an atlas read with texture2D.
namespace obscura {

enum class EnvironmentLayout { MipChain, Atlas };
const char* environmentLayoutName(EnvironmentLayout layout);  // "mipchain", "atlas"

// Which levels the hardware's filter reads (environment/Environment.h, "Storage"): by the measured bound, or one
// storage forced (the tests and benchmarks compare both).
enum class EnvironmentFiltering { Measured, ByHand, Hardware };

}  // namespace obscura
