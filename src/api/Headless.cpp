// obscura/headless.h over platform/HeadlessContext.
#include "obscura/headless.h"

#include <EGL/egl.h>

#include "platform/HeadlessContext.h"

// OSMesa's loader, declared as <GL/osmesa.h> does (that header pulls in desktop <GL/gl.h>, which must not meet the
// GLES 2 headers of this file).
extern "C" {
typedef void (*OSMESAproc)();
OSMESAproc OSMesaGetProcAddress(const char* funcName);
}

namespace obscura::api {
namespace {

void* eglProc(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }
void* osmesaProc(const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); }

}  // namespace

struct HeadlessContext::Impl {
  explicit Impl(HeadlessBackend backend) : context(backend) {}
  obscura::HeadlessContext context;
};

HeadlessContext::HeadlessContext(Backend backend) : backend_(backend) {
  try {
    impl_ = std::make_unique<Impl>(backend == Backend::Egl ? HeadlessBackend::Egl : HeadlessBackend::OSMesa);
  } catch (const std::exception& e) {
    throw Error(e.what());
  }
}
HeadlessContext::~HeadlessContext() = default;

ProcAddressLoader HeadlessContext::getProcAddress() const { return backend_ == Backend::Egl ? &eglProc : &osmesaProc; }

const char* HeadlessContext::backendName(Backend backend) { return backend == Backend::Egl ? "egl" : "osmesa"; }

HeadlessContext::Backend HeadlessContext::parseBackend(const std::string& name) {
  if (name == "egl") return Backend::Egl;
  if (name == "osmesa") return Backend::OSMesa;
  throw Error("backend: expected egl or osmesa, got '" + name + "'");
}

}  // namespace obscura::api
