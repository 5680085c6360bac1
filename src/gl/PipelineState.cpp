#include "gl/PipelineState.h"

#include <algorithm>

#include "gl/GlApi.h"

namespace obscura::gl {
namespace {
// GLES 2's 8 units, the ninth that the lighting's BRDF table takes where the context has one, and the tenth that it
// leaves to its fused stages' own textures (gpu/TextureUnits.h).
constexpr int kTextureUnits = 10;
constexpr GLuint kAttributeSlots = 8;  // the GLES 2 minimum (skinned and morphed draws use them all)

bool g_vertexArrays = false;
int g_combinedTextureUnits = 8;  // the GLES 2 minimum until GlCaps::query says more (asked once, not per restore)

int textureUnitsInUse() { return std::min(kTextureUnits, g_combinedTextureUnits); }
}  // namespace

void restoreBaselineState() {
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glDisable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ZERO);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(0.0f, 0.0f);
  glDisable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 0, 0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glClearStencil(0);
  glUseProgram(0);
  if (g_vertexArrays) glBindVertexArrayOES(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  for (int unit = textureUnitsInUse() - 1; unit >= 0; --unit) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  for (GLuint slot = 0; slot < kAttributeSlots; ++slot) glDisableVertexAttribArray(slot);
}

void unbindTextureUnits(std::initializer_list<int> units) {
  for (int unit : units) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glActiveTexture(GL_TEXTURE0);
}

void setBaselineContext(bool vertexArrays, int combinedTextureUnits) {
  g_vertexArrays = vertexArrays;
  g_combinedTextureUnits = combinedTextureUnits;
}

std::string baselineStateDifferences() {
  std::string out;
  auto expect = [&](bool ok, const char* what) {
    if (!ok) out += std::string(out.empty() ? "" : ", ") + what;
  };
  GLint value = 0;
  expect(!glIsEnabled(GL_DEPTH_TEST), "depth test enabled");
  expect(!glIsEnabled(GL_CULL_FACE), "face culling enabled");
  expect(!glIsEnabled(GL_BLEND), "blending enabled");
  expect(!glIsEnabled(GL_SCISSOR_TEST), "scissor test enabled");
  expect(!glIsEnabled(GL_POLYGON_OFFSET_FILL), "polygon offset enabled");
  expect(!glIsEnabled(GL_STENCIL_TEST), "stencil test enabled");
  GLboolean depthMask = GL_FALSE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
  expect(depthMask == GL_TRUE, "depth writes off");
  glGetIntegerv(GL_FRONT_FACE, &value);
  expect(value == GL_CCW, "front face not CCW");
  glGetIntegerv(GL_CURRENT_PROGRAM, &value);
  expect(value == 0, "a program is bound");
  if (g_vertexArrays) {
    // First: the element buffer and the attribute arrays below are the bound object's.
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING_OES, &value);
    expect(value == 0, "a vertex array object is bound");
  }
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &value);
  expect(value == 0, "an array buffer is bound");
  glGetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &value);
  expect(value == 0, "an element buffer is bound");
  glGetIntegerv(GL_ACTIVE_TEXTURE, &value);
  expect(value == GL_TEXTURE0, "texture unit 0 not active");
  for (int unit = 0; unit < textureUnitsInUse(); ++unit) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &value);
    expect(value == 0, "a texture is bound");
    glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &value);
    expect(value == 0, "a cube map is bound");
  }
  glActiveTexture(GL_TEXTURE0);
  for (GLuint slot = 0; slot < kAttributeSlots; ++slot) {
    glGetVertexAttribiv(slot, GL_VERTEX_ATTRIB_ARRAY_ENABLED, &value);
    expect(value == 0, "a vertex attribute array is enabled");
  }
  return out;
}

}  // namespace obscura::gl
