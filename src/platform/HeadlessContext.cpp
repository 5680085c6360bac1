#include "platform/HeadlessContext.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "base/Error.h"
#include "gl/GlLoader.h"
#include "platform/OsMesaContext.h"

namespace obscura {

HeadlessBackend parseBackend(const std::string& name) {
  if (name == "osmesa") return HeadlessBackend::OSMesa;
  if (name == "egl") return HeadlessBackend::Egl;
  throw InputError("backend: expected osmesa or egl, got '" + name + "'");
}

const char* backendName(HeadlessBackend backend) { return backend == HeadlessBackend::OSMesa ? "osmesa" : "egl"; }

struct HeadlessContext::Impl {
  std::unique_ptr<OsMesaContext> osmesa;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  void createEgl() {
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) throw GlError("EGL: eglGetPlatformDisplayEXT is not available");
    // Mesa's surfaceless platform; where the vendor's EGL has none (NVIDIA's), the first device of
    // EGL_EXT_platform_device, which is as headless.
    EGLint major = 0, minor = 0;
    display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY && !eglInitialize(display, &major, &minor)) display = EGL_NO_DISPLAY;
    if (display == EGL_NO_DISPLAY) {
      auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      EGLDeviceEXT device = nullptr;
      EGLint devices = 0;
      if (queryDevices && queryDevices(1, &device, &devices) && devices > 0)
        display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
      if (display != EGL_NO_DISPLAY && !eglInitialize(display, &major, &minor)) display = EGL_NO_DISPLAY;
    }
    if (display == EGL_NO_DISPLAY)
      throw GlError("EGL: no surfaceless display and no EGL device (is libegl-mesa0 installed?)");
    if (!eglBindAPI(EGL_OPENGL_ES_API)) throw GlError("EGL: OpenGL ES is not supported");
    // The surfaceless platform offers pbuffer configurations only (the default asks for a window).
    const EGLint configAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT,
                                       EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &count) || count < 1)
      throw GlError("EGL: no OpenGL ES 2 configuration");
    const EGLint contextAttributes[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) throw GlError("EGL: cannot create an OpenGL ES 2 context");
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
      throw GlError("EGL: cannot make the context current without a surface");
    std::string missing;
    if (!gl::loadGles2([](const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }, &missing))
      throw GlError("EGL: the context lacks the GLES 2 entry point " + missing);
  }

  ~Impl() {
    if (display != EGL_NO_DISPLAY) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
      eglTerminate(display);
    }
  }
};

HeadlessContext::HeadlessContext(HeadlessBackend backend) : backend_(backend), impl_(std::make_unique<Impl>()) {
  if (backend == HeadlessBackend::OSMesa) impl_->osmesa = std::make_unique<OsMesaContext>();
  else impl_->createEgl();
  caps_ = gl::GlCaps::query();
}

HeadlessContext::~HeadlessContext() = default;

}  // namespace obscura
