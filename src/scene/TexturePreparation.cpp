#include "scene/TexturePreparation.h"

#include <algorithm>

#include "scene/ImageIo.h"

namespace obscura {
namespace {

// GL enum values (the scene library does not include GL headers).
constexpr int kNearest = 0x2600, kLinear = 0x2601;
constexpr int kNearestMipmapNearest = 0x2700, kLinearMipmapNearest = 0x2701, kNearestMipmapLinear = 0x2702,
              kLinearMipmapLinear = 0x2703;
constexpr int kRepeat = 0x2901, kClampToEdge = 0x812F, kMirroredRepeat = 0x8370;

bool isPowerOfTwo(int v) { return v > 0 && (v & (v - 1)) == 0; }
int nextPowerOfTwo(int v) {
  int p = 1;
  while (p < v) p *= 2;
  return p;
}
bool usesMipmaps(int minFilter) {
  return minFilter == kNearestMipmapNearest || minFilter == kLinearMipmapNearest ||
         minFilter == kNearestMipmapLinear || minFilter == kLinearMipmapLinear;
}
int validWrap(int wrap) { return wrap == kClampToEdge || wrap == kMirroredRepeat ? wrap : kRepeat; }
int validMinFilter(int filter) {
  return filter == kNearest || filter == kLinear || usesMipmaps(filter) ? filter : kLinearMipmapLinear;
}
int validMagFilter(int filter) { return filter == kNearest ? kNearest : kLinear; }

}  // namespace

PreparedTexture prepareTextureForGles2(const Image& image, const SamplerState& sampler, int maxTextureSize) {
  PreparedTexture out;
  out.sampler.minFilter = validMinFilter(sampler.minFilter);
  out.sampler.magFilter = validMagFilter(sampler.magFilter);
  out.sampler.wrapS = validWrap(sampler.wrapS);
  out.sampler.wrapT = validWrap(sampler.wrapT);
  const bool needsPowerOfTwo = usesMipmaps(out.sampler.minFilter) || out.sampler.wrapS != kClampToEdge ||
                               out.sampler.wrapT != kClampToEdge;
  int width = image.width, height = image.height;
  if (needsPowerOfTwo) {
    width = nextPowerOfTwo(width);
    height = nextPowerOfTwo(height);
  }
  const int maxSize = std::max(maxTextureSize, 1);
  if (std::max(width, height) > maxSize) {
    if (needsPowerOfTwo) {
      // Halving keeps both sides powers of two.
      while (std::max(width, height) > maxSize) {
        width = std::max(1, width / 2);
        height = std::max(1, height / 2);
      }
    } else {
      const int larger = std::max(width, height);
      width = std::max(1, static_cast<int>(static_cast<long long>(width) * maxSize / larger));
      height = std::max(1, static_cast<int>(static_cast<long long>(height) * maxSize / larger));
    }
  }
  out.image = (width == image.width && height == image.height) ? image : resizeImage(image, width, height);
  out.mipmaps = usesMipmaps(out.sampler.minFilter) && isPowerOfTwo(width) && isPowerOfTwo(height);
  return out;
}

}  // namespace obscura
