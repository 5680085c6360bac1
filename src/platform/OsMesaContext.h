#pragma once
// An OSMesa context made current on construction, with the GLES 2 dispatch table loaded from it. Its own
// translation unit, because <GL/osmesa.h> includes desktop <GL/gl.h>.

namespace obscura {

class OsMesaContext {
 public:
  OsMesaContext();  // throws GlError with the reason
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

 private:
  void* context_ = nullptr;
  unsigned char buffer_[4 * 4 * 4] = {};
};

}  // namespace obscura
