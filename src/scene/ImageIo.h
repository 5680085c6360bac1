#pragma once
// PNG in and out (stb), and resampling, for rendered images and glTF textures.
#include <string>

#include "scene/Scene.h"

namespace obscura {

// Writes RGBA8 rows top to bottom. Throws InputError naming the path if it cannot be written.
void writePng(const std::string& path, const Image& image);
// Reads any PNG as RGBA8. Throws InputError naming the path and the decoder's reason.
Image readPng(const std::string& path);
// Resamples to width x height (stb_image_resize, sRGB-aware filtering of colour, linear alpha).
Image resizeImage(const Image& image, int width, int height);

}  // namespace obscura
