#pragma once
// Native stand-ins for the Emscripten declarations the page's C++ side uses (src/apps/obscura_web.cpp,
// src/apps/obscura_web_geometry.cpp, src/platform/WebCanvas.cpp), so that code builds natively, unchanged, and runs
// in the test suite, sanitized included (tests/test_web_api.cpp). Declared as Emscripten 3.1 declares them; the
// definitions are in tests/web/NativePage.cpp. A new Emscripten call in those files needs its stand-in here.
#include <emscripten/html5.h>

#define EMSCRIPTEN_KEEPALIVE __attribute__((used))
#define EM_LOG_CONSOLE 1
#define EM_LOG_ERROR 4
// A JavaScript function defined in C++: natively it does nothing (its parameters go unused).
#define EM_JS(ret, name, params, ...) \
  ret name params {}

extern "C" {
void emscripten_log(int flags, const char* format, ...) __attribute__((format(printf, 2, 3)));
double emscripten_get_now(void);
}
