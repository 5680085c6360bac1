#pragma once
// What a context can do, read once after it is made current and handed to the Renderer. Optional features are used
// only through these flags, each with a tested fallback; tests switch flags off to exercise the fallbacks.
#include <string>
#include <unordered_set>

#include "gl/GlApi.h"

namespace obscura {

// Limits of the vertex stage to simulate: the renderer uses the smaller of these and the context's. gles2Minimum()
// is what every GLES 2 / WebGL 1 context guarantees: 128 uniform vectors, 8 attributes, no vertex texture units.
struct VertexLimits {
  int uniformVectors = 128, attributes = 8, textureUnits = 0;
  static VertexLimits gles2Minimum() { return {}; }
};

// Limits of the fragment stage (and the program's combined texture units) to simulate, as VertexLimits does for the
// vertex stage. gles2Minimum(): 16 uniform vectors, 8 texture units in the fragment stage, 8 in all. They set the
// punctual lights per draw (effects/lighting/LightingEffect.h) and the texture units (gpu/TextureUnits.h).
struct FragmentLimits {
  int uniformVectors = 16, textureUnits = 8, combinedTextureUnits = 8;
  static FragmentLimits gles2Minimum() { return {}; }
};

}  // namespace obscura

namespace obscura::gl {

struct GlCaps {
  std::string vendor, renderer, version, shadingLanguage;
  std::unordered_set<std::string> extensions;

  bool fragmentHighp = false;           // GL_HIGH_FLOAT in fragment shaders (needed by the 16-bit depth packing)
  bool elementIndexUint = false;        // OES_element_index_uint: 32-bit indices
  bool depth24 = false;                 // OES_depth24 renderbuffers
  bool packedDepthStencil = false;      // a depth + stencil renderbuffer (WebGL 1 core, OES_packed_depth_stencil)
  bool standardDerivatives = false;     // OES_standard_derivatives
  bool shaderTextureLod = false;        // EXT_shader_texture_lod: texture2DLodEXT in fragment shaders
  bool fboRenderMipmap = false;         // OES_fbo_render_mipmap: render into mip levels > 0
  bool timerQuery = false;              // EXT_disjoint_timer_query
  bool drawBuffers = false;             // EXT_draw_buffers / WEBGL_draw_buffers: several colour targets per pass
  GLint maxDrawBuffers = 1;
  // OES_vertex_array_object (core in desktop GL 3.0): the scene's pieces keep their vertex streams in one object
  // each, bound with one call per draw (gpu/GpuScene.h).
  bool vertexArrayObject = false;
  bool desktopGl = false;               // a desktop GL context running GLSL ES (OSMesa): sized float formats
  bool textureFloat = false;            // OES_texture_float (core in desktop GL 3.0): RGBA float textures to sample
  // OES_texture_half_float and OES_texture_half_float_linear (core in desktop GL 3.0): half-float textures the
  // hardware's bilinear filter reads (the environment's levels: environment/Environment.h).
  bool textureHalfFloatLinear = false;
  // The vertex stage's limits, which size skinning and morphing (gpu/GpuScene.h). GLES 2 guarantees 128 uniform
  // vectors, 8 attributes and no texture units.
  GLint maxVertexUniformVectors = 128, maxVertexAttribs = 8, maxVertexTextureImageUnits = 0;
  // The fragment stage's and the whole program's: they size the lighting's punctual lights per draw and decide which
  // texture units the lighting pass may take (gpu/TextureUnits.h). GLES 2 guarantees 16 uniform vectors, 8 texture
  // units in the fragment stage and 8 in all.
  GLint maxFragmentUniformVectors = 16, maxTextureImageUnits = 8, maxCombinedTextureImageUnits = 8;
  GLint maxTextureSize = 0, maxRenderbufferSize = 0, maxViewportWidth = 0, maxViewportHeight = 0;

  bool has(const std::string& extension) const { return extensions.count(extension) != 0; }
  // Largest render size this context accepts for a W x H target.
  int maxRenderSize() const;

  static GlCaps query();
};

}  // namespace obscura::gl
