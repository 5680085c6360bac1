#include "scene/ImageIo.h"

#include <stb_image.h>
#include <stb_image_resize.h>
#include <stb_image_write.h>

#include "base/Error.h"

namespace obscura {

void writePng(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || image.rgba.size() != size_t(image.width) * image.height * 4)
    throw InputError(path + ": refusing to write an empty or inconsistent image");
  if (!stbi_write_png(path.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4))
    throw InputError(path + ": cannot write PNG");
}

Image readPng(const std::string& path) {
  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &width, &height, &channels, 4);
  if (!pixels) throw InputError(path + ": cannot read image (" + stbi_failure_reason() + ")");
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(pixels, pixels + size_t(width) * height * 4);
  stbi_image_free(pixels);
  return image;
}

Image resizeImage(const Image& image, int width, int height) {
  Image out;
  out.width = width;
  out.height = height;
  out.rgba.resize(size_t(width) * height * 4);
  stbir_resize_uint8_srgb(image.rgba.data(), image.width, image.height, 0, out.rgba.data(), width, height, 0, 4, 3, 0);
  return out;
}

}  // namespace obscura
