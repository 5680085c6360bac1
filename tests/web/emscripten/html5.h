#pragma once
// Native stand-ins (tests/web/emscripten/emscripten.h says why).
#include <emscripten/html5_webgl.h>

typedef int EMSCRIPTEN_RESULT;
#define EMSCRIPTEN_RESULT_SUCCESS 0

extern "C" {
void emscripten_request_animation_frame_loop(EM_BOOL (*callback)(double time, void* userData), void* userData);
EMSCRIPTEN_RESULT emscripten_get_element_css_size(const char* target, double* width, double* height);
double emscripten_get_device_pixel_ratio(void);
EMSCRIPTEN_RESULT emscripten_get_canvas_element_size(const char* target, int* width, int* height);
EMSCRIPTEN_RESULT emscripten_set_canvas_element_size(const char* target, int width, int height);
}
