#include "platform/OsMesaContext.h"

#include <GL/osmesa.h>

#include <string>

#include "base/Error.h"
#include "gl/GlLoader.h"

namespace obscura {

OsMesaContext::OsMesaContext() {
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 0,
                            OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0};
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!context) throw GlError("OSMesa: cannot create a context (is libosmesa6 installed?)");
  context_ = context;
  // The default framebuffer is never drawn to (every pass renders into framebuffer objects), but OSMesa needs one.
  if (!OSMesaMakeCurrent(context, buffer_, GL_UNSIGNED_BYTE, 4, 4)) {
    OSMesaDestroyContext(context);
    throw GlError("OSMesa: cannot make the context current");
  }
  std::string missing;
  if (!gl::loadGles2([](const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); },
                     &missing)) {
    OSMesaDestroyContext(context);
    throw GlError("OSMesa: the context lacks the GLES 2 entry point " + missing);
  }
}

OsMesaContext::~OsMesaContext() {
  OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);  // release the framebuffer OSMesa made for the context
  OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

}  // namespace obscura
