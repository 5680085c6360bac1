// The one translation unit that compiles the implementations of the header-only libraries (tinygltf, stb_image,
// stb_image_write, stb_image_resize), on every platform alike.
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_RESIZE_IMPLEMENTATION
#define TINYGLTF_IMPLEMENTATION
// tiny_gltf.h includes stb_image.h and stb_image_write.h itself; including them here too would compile their
// implementations twice.
#include <tiny_gltf.h>
#include <stb_image_resize.h>
