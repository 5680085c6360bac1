#pragma once
// glTF textures made legal for OpenGL ES 2 / WebGL 1, on the CPU so the rules are testable without a context:
// - a non-power-of-two image may be sampled only with CLAMP_TO_EDGE wrapping and without mipmaps; one that asks
//   for repeat / mirrored-repeat wrapping or a mipmap filter is resampled to the next power of two;
// - an image larger than the context's maximum texture size is scaled down (keeping powers of two);
// - invalid or missing filter / wrap enums fall back to glTF's defaults (LINEAR_MIPMAP_LINEAR, LINEAR, REPEAT).
#include "scene/Scene.h"

namespace obscura {

struct PreparedTexture {
  Image image;
  SamplerState sampler;  // every field a valid GLES 2 enum
  bool mipmaps = false;  // generate mipmaps (only ever for power-of-two images)
};

PreparedTexture prepareTextureForGles2(const Image& image, const SamplerState& sampler, int maxTextureSize);

}  // namespace obscura
