#include "gl/GlCaps.h"

#include <algorithm>
#include <sstream>

#include "gl/PipelineState.h"

namespace obscura::gl {
namespace {
std::string glString(GLenum name) {
  const GLubyte* s = glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : "";
}
}  // namespace

int GlCaps::maxRenderSize() const {
  return std::min({maxTextureSize, maxRenderbufferSize, maxViewportWidth, maxViewportHeight});
}

GlCaps GlCaps::query() {
  GlCaps caps;
  caps.vendor = glString(GL_VENDOR);
  caps.renderer = glString(GL_RENDERER);
  caps.version = glString(GL_VERSION);
  caps.shadingLanguage = glString(GL_SHADING_LANGUAGE_VERSION);
  std::istringstream list(glString(GL_EXTENSIONS));
  for (std::string ext; list >> ext;) {
    // WebGL reports extensions without the GL_ prefix; normalise to the GLES spelling.
    if (ext.rfind("GL_", 0) != 0) ext = "GL_" + ext;
    caps.extensions.insert(ext);
  }

  GLint range[2] = {0, 0};
  GLint precision = 0;
  glGetShaderPrecisionFormat(GL_FRAGMENT_SHADER, GL_HIGH_FLOAT, range, &precision);
  // GLSL ES 1.00 highp float is at least 2^-16 relative precision (precision >= 16); 0 means not supported.
  caps.fragmentHighp = precision >= 16;

  // Desktop GL (OSMesa) has these as core features but does not list the ES extension names.
  const bool desktopGl = caps.version.find("OpenGL ES") == std::string::npos &&
                         caps.version.find("WebGL") == std::string::npos;
  caps.elementIndexUint = desktopGl || caps.has("GL_OES_element_index_uint");
  caps.depth24 = desktopGl || caps.has("GL_OES_depth24");
  // WebGL 1 has a DEPTH_STENCIL renderbuffer in its core; GLES 2 needs OES_packed_depth_stencil (desktop GL 3.0 has
  // DEPTH24_STENCIL8 as core).
  const bool webGl = caps.version.find("WebGL") != std::string::npos;
  caps.packedDepthStencil = webGl || desktopGl || caps.has("GL_OES_packed_depth_stencil");
  caps.standardDerivatives = caps.has("GL_OES_standard_derivatives");
  caps.shaderTextureLod = caps.has("GL_EXT_shader_texture_lod");
  caps.fboRenderMipmap = caps.has("GL_OES_fbo_render_mipmap");
  caps.timerQuery = caps.has("GL_EXT_disjoint_timer_query");
  // Natively the entry point must have loaded too (GlApi.cpp); a desktop context's ES shaders cannot use the ES
  // extension, so OSMesa's compatibility context, which does not list it, takes the path without it.
#if OBSCURA_GL_DIRECT
  const bool entryPoint = true;  // linked from Emscripten's GL library
#else
  const bool entryPoint = raw::glDrawBuffersEXT != nullptr;
#endif
  caps.drawBuffers = (caps.has("GL_EXT_draw_buffers") || caps.has("GL_WEBGL_draw_buffers")) && entryPoint;
  if (caps.drawBuffers) glGetIntegerv(GL_MAX_DRAW_BUFFERS_EXT, &caps.maxDrawBuffers);

  // Vertex array objects: OES_vertex_array_object on GLES 2 / WebGL 1, core since desktop GL 3.0 (or
  // ARB_vertex_array_object), each only where its entry points loaded.
  const bool vertexArrayEntryPoints = selectVertexArrayEntryPoints(desktopGl);
  const bool desktopVertexArrays =
      caps.has("GL_ARB_vertex_array_object") || (!caps.version.empty() && caps.version[0] >= '3');
  caps.vertexArrayObject =
      vertexArrayEntryPoints && (desktopGl ? desktopVertexArrays : caps.has("GL_OES_vertex_array_object"));

  caps.desktopGl = desktopGl;
  caps.textureFloat = desktopGl || caps.has("GL_OES_texture_float");
  caps.textureHalfFloatLinear =
      desktopGl || (caps.has("GL_OES_texture_half_float") && caps.has("GL_OES_texture_half_float_linear"));
  glGetIntegerv(GL_MAX_VERTEX_UNIFORM_VECTORS, &caps.maxVertexUniformVectors);
  glGetIntegerv(GL_MAX_VERTEX_ATTRIBS, &caps.maxVertexAttribs);
  glGetIntegerv(GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, &caps.maxVertexTextureImageUnits);
  glGetIntegerv(GL_MAX_FRAGMENT_UNIFORM_VECTORS, &caps.maxFragmentUniformVectors);
  glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &caps.maxTextureImageUnits);
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &caps.maxCombinedTextureImageUnits);
  setBaselineContext(caps.vertexArrayObject, caps.maxCombinedTextureImageUnits);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &caps.maxTextureSize);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &caps.maxRenderbufferSize);
  GLint viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  caps.maxViewportWidth = viewport[0];
  caps.maxViewportHeight = viewport[1];
  return caps;
}

}  // namespace obscura::gl
