// The binding cache (gl/BindingCache.h): within a scope the texture, program, vertex array and viewport bindings are
// made only where a call depends on them, the state a draw or a query sees is the one asked for, a deleted object is
// unbound as GL unbinds it, the scope's end leaves what was asked last, and frames are the same bytes with and
// without it.
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "gl/BindingCache.h"
#include "gl/GlApi.h"
#include "gl/PipelineState.h"
#include "gl/Program.h"
#include "gl/RenderTarget.h"
#include "scene/BuiltinScene.h"

using namespace obscura;

namespace {

GLint boundTexture(GLenum unit) {
  GLint bound = -1;
  glActiveTexture(unit);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  glActiveTexture(GL_TEXTURE0);
  return bound;
}

std::uint64_t made() { return gl::bindings::counts().made; }

const char* kVertex = "#version 100\nattribute vec2 a_position; void main() { gl_Position = vec4(a_position, 0, 1); }";
const char* kFragment =
    "#version 100\nprecision mediump float; uniform float u_value; void main() { gl_FragColor = vec4(u_value); }";

}  // namespace

TEST(BindingCache, MakesTheBindingsOnlyWhereACallDependsOnThem) {
  test::context();
  const gl::Texture2D a(4, 4, GL_NEAREST), b(4, 4, GL_NEAREST);
  gl::Program program("binding-cache", kVertex, kFragment);
  {
    const gl::DeferredBindings scope;
    const std::uint64_t start = made();
    // Bound, unbound and bound again, with calls between that depend on no binding: nothing made yet.
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, a.id());
    glBindTexture(GL_TEXTURE_2D, 0);
    glViewport(0, 0, 4, 4);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glViewport(0, 0, 2, 2);
    glBindTexture(GL_TEXTURE_2D, a.id());
    glUseProgram(program.id());
    EXPECT_EQ(made() - start, 0u);
    // A uniform needs the program only: one call.
    glUniform1f(glGetUniformLocation(program.id(), "u_value"), 0.5f);
    EXPECT_EQ(made() - start, 1u);
    // A query needs everything: the unit and its texture (the unit asked for last, 3, is then active), and the
    // viewport asked for last.
    GLint bound = -1, active = -1, viewport[4] = {};
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(static_cast<GLuint>(bound), a.id());
    EXPECT_EQ(active, GL_TEXTURE3);
    EXPECT_EQ(viewport[2], 2);
    EXPECT_EQ(made() - start, 4u);
    // The same bindings asked for again cost nothing.
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, a.id());
    glUseProgram(program.id());
    glViewport(0, 0, 2, 2);
    GLint current = -1;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    EXPECT_EQ(static_cast<GLuint>(current), program.id());
    EXPECT_EQ(made() - start, 4u);
    // Left bound to unit 1 and the program in use, unbound at the end: the scope's end makes that.
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, b.id());
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glUseProgram(0);
  }
  EXPECT_EQ(gl::baselineStateDifferences(), "");
  EXPECT_EQ(boundTexture(GL_TEXTURE3), 0);
}

TEST(BindingCache, ADeletedTextureIsUnboundAsGlUnbindsIt) {
  test::context();
  const gl::DeferredBindings scope;
  for (bool madeBeforeDeleting : {true, false}) {
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, texture);
    if (madeBeforeDeleting) {
      EXPECT_EQ(static_cast<GLuint>(boundTexture(GL_TEXTURE2)), texture);
    }
    glActiveTexture(GL_TEXTURE2);
    glDeleteTextures(1, &texture);
    EXPECT_EQ(boundTexture(GL_TEXTURE2), 0) << madeBeforeDeleting;
    // A new texture may take the deleted one's name: binding it must reach GL.
    GLuint next = 0;
    glGenTextures(1, &next);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, next);
    EXPECT_EQ(static_cast<GLuint>(boundTexture(GL_TEXTURE2)), next) << madeBeforeDeleting;
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glDeleteTextures(1, &next);
  }
}

// Frames with every kind of pass (the geometry passes, skinned and morphed draws, the transparent layer, every
// effect, the debug views, the split view) drawn by a Renderer without the per-pass checks (whose queries make every
// binding after each pass): the same bytes with the cache and without, and fewer binding calls made with it.
TEST(BindingCache, FramesAreTheSameBytesWithAndWithoutIt) {
  std::vector<test::FramedScene> cases;
  cases.push_back(test::framedBuiltinScene(96, 64));
  cases.push_back(test::framedFile("simple_skin", test::assimpModels() + "/simple_skin/simple_skin.gltf", 96, 64));
  cases.push_back(test::framedFile(
      "AnimatedMorphCube",
      test::assimpModels() + "/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf", 96, 64));
  cases.push_back(test::framedScene("cut-out blend", test::cutOutQuadOnAFloor(AlphaMode::Blend), 96, 64));
  RenderSettings low;
  low.set("preset", "low");
  const std::vector<RenderSettings> settings = {RenderSettings{}, RenderSettings::everyEffectOn(), low};
  const std::vector<View> views = {View::Final, View::Split, View::Ao, View::Normals, View{"scene-color"}};
  for (const test::FramedScene& c : cases) {
    std::vector<test::RenderedImage> frames[2];
    gl::bindings::Counts calls[2];
    for (int deferring : {0, 1}) {
      gl::bindings::setDeferring(deferring != 0);
      Renderer renderer(test::context().caps(), RendererOptions{});
      renderer.setScene(c.scene);
      const gl::bindings::Counts before = gl::bindings::counts();
      for (const RenderSettings& s : settings)
        for (const View& view : views)
          for (double time : {0.25, 0.5}) {  // two frames: the second has history
            FrameOptions options;
            options.time = time;
            frames[deferring].push_back(test::render(renderer, c.camera, s, view, options));
          }
      calls[deferring] = {gl::bindings::counts().asked - before.asked, gl::bindings::counts().made - before.made};
      EXPECT_EQ(gl::baselineStateDifferences(), "") << c.name;
    }
    gl::bindings::setDeferring(true);
    ASSERT_EQ(frames[0].size(), frames[1].size());
    for (size_t i = 0; i < frames[0].size(); ++i)
      EXPECT_EQ(test::worstByteDifference(frames[0][i], frames[1][i]), 0) << c.name << ", frame " << i;
    EXPECT_EQ(calls[0].made, calls[0].asked) << c.name;
    EXPECT_EQ(calls[1].asked, calls[0].asked) << c.name;
    EXPECT_LT(calls[1].made, calls[1].asked * 3 / 4) << c.name;
  }
}
