// Every program variant the renderer can build compiles and links on the headless context; a broken shader is
// reported with the program's name and the driver's log. (tests/check_shaders_glslang.sh validates the same text
// with glslangValidator as GLSL ES 1.00.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <tuple>

#include "TestSupport.h"
#include "base/Error.h"
#include "effects/dither/Dither.h"
#include "effects/fog/FogEffect.h"
#include "effects/grading/ColorGrading.h"
#include "effects/grain/Grain.h"
#include "effects/lighting/LightingEffect.h"
#include "effects/tonemap/TonemapEffect.h"
#include "effects/vignette/Vignette.h"
#include "frame/ProgramCache.h"
#include "frame/Stage.h"
#include "effects/transparency/TransparencyEffect.h"

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "renderer/EffectTable.h"
#include "gl/UniformPacking.h"

using namespace obscura;

TEST(Shaders, EveryVariantCompilesAndLinks) {
  test::context();
  const std::vector<ProgramSpec> specs = Renderer::allProgramSpecs();
  EXPECT_GE(specs.size(), 20u);
  const gl::GlCaps& caps = test::context().caps();
  for (const ProgramSpec& spec : specs) {
    // Variants that need an extension build only where the context has it (the page tests them in the browser).
    if (!std::all_of(spec.extensions.begin(), spec.extensions.end(), [&](const std::string& e) { return caps.has(e); }))
      continue;
    try {
      const gl::Program program = spec.build();
      EXPECT_NE(program.id(), 0u) << spec.name;
    } catch (const GlError& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

namespace {

// The error of "broken[test]", whose fragment stage reads an undefined_symbol: the program, the stage and the log.
void expectBrokenShaderNamed(const GlError& e) {
  const std::string message = e.what();
  EXPECT_NE(message.find("broken[test]"), std::string::npos) << message;
  EXPECT_NE(message.find("fragment"), std::string::npos) << message;
  EXPECT_NE(message.find("undefined_symbol"), std::string::npos) << message;
}

}  // namespace

TEST(Shaders, CompileFailureNamesTheProgramAndQuotesTheLog) {
  test::context();
  try {
    gl::Program("broken[test]", ShaderLibrary::composeText("void main() { gl_Position = vec4(0.0); }", {}, {}),
                ShaderLibrary::composeText("void main() { gl_FragColor = undefined_symbol; }", {}, {}));
    FAIL() << "a broken shader compiled";
  } catch (const GlError& e) {
    expectBrokenShaderNamed(e);
  }
}

TEST(Shaders, LinkFailureNamesTheProgramAndQuotesTheLog) {
  test::context();
  try {
    // Each stage compiles; the fragment stage reads a varying the vertex stage never declares, and both use a uniform
    // of one name and two types: link errors both (GLSL ES 1.00, 4.3.5 and 4.3.4). NVIDIA's driver (580) links the
    // first alone.
    gl::Program("unlinkable[test]",
                ShaderLibrary::composeText("uniform float u_shared;\n"
                                           "void main() { gl_Position = vec4(u_shared); }",
                                           {}, {}),
                ShaderLibrary::composeText("precision mediump float;\nvarying vec3 v_missing;\nuniform vec2 u_shared;\n"
                                           "void main() { gl_FragColor = vec4(v_missing, u_shared.x); }",
                                           {}, {}));
    FAIL() << "a program whose stages disagree linked";
  } catch (const GlError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'unlinkable[test]' failed to link: "), std::string::npos) << message;
    EXPECT_GT(message.size(), std::string("shader program 'unlinkable[test]' failed to link: ").size() + 5)
        << "no driver log quoted: " << message;
  }
}

// A program begun (gl::Program::begin: compiled and linked without waiting) is finished by its first use, and is then
// the program built at once; one that does not compile fails there with the same message (Renderer::prepare).
TEST(Shaders, ABegunProgramIsFinishedByItsFirstUseAndABrokenOneFailsThere) {
  test::context();
  const ProgramSpec spec{"blit[test]", "lib/fullscreen.vert", "frame/debug_view.frag", {{"VIEW_DECODING", "5"}}};
  const ProgramSpec broken{"broken[test]", "lib/fullscreen.vert", "", {}, {},
                           "void main() { gl_FragColor = undefined_symbol; }"};
  ProgramCache cache(true);
  ProgramVariants<int> variants(cache);
  const gl::LiveObjects before = gl::liveObjects();
  {
    const ProgramCache::Rehearsal rehearsal(cache);
    const gl::Program& standIn = cache.get(spec);
    EXPECT_TRUE(standIn.linked());
    EXPECT_TRUE(standIn.uniformNames().empty()) << "a stand-in: the uniforms set on it go nowhere";
    standIn.use();
    standIn.set("u_source", 0);  // lenient, whatever the cache's programs are
    glUseProgram(0);
    EXPECT_EQ(&cache.get(spec), &standIn) << "the stand-in again";
    EXPECT_EQ(&variants(1, [&] { return spec; }), &standIn);
    EXPECT_NO_THROW(cache.get(broken)) << "a begun program's errors wait for its first use";
    EXPECT_EQ(cache.size(), 0u) << "noted, and begun at the rehearsal's end";
  }
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_EQ(cache.pending(), 2u);
  // The two begun (each a program and its two stages, kept until finished); the stand-in is gone.
  EXPECT_EQ(gl::liveObjects().programs, before.programs + 2);
  EXPECT_EQ(gl::liveObjects().shaders, before.shaders + 4);
  const gl::Program& program = cache.get(spec);
  EXPECT_TRUE(program.linked());
  EXPECT_EQ(cache.pending(), 1u);
  EXPECT_EQ(program.uniformNames(), spec.build().uniformNames());
  EXPECT_EQ(&variants(1, [&] { return spec; }), &program) << "the variants kept no stand-in";
  try {
    cache.get(broken);
    FAIL() << "a broken shader compiled";
  } catch (const GlError& e) {
    expectBrokenShaderNamed(e);
  }
  EXPECT_EQ(cache.pending(), 1u) << "the broken one is still begun, and fails at each use";
  EXPECT_THROW(cache.get(broken), GlError);
  // A program begun and never finished (its frame was not drawn) is dropped, with its stages.
  EXPECT_EQ(cache.dropPending(), 1u);
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_EQ(cache.pending(), 0u);
  EXPECT_EQ(gl::liveObjects().programs, before.programs + 1);
  EXPECT_EQ(gl::liveObjects().shaders, before.shaders);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(Shaders, SourcesAreGlslEs100WithoutForbiddenFeatures) {
  for (const ProgramSpec& spec : Renderer::allProgramSpecs()) {
    for (std::string source : {spec.vertexSource(), spec.fragmentSource()}) {
      source = ShaderLibrary::withoutComments(source);  // the code alone
      EXPECT_EQ(source.rfind("#version 100\n", 0), 0u) << spec.name;
      // No bitwise operators, no texelFetch, no integer textures: GLSL ES 1.00 has none of them.
      for (const char* forbidden : {"texelFetch", "textureSize", "<<", ">>", " ^ ", " | ", " & ", "uint", "flat "})
        EXPECT_EQ(source.find(forbidden), std::string::npos) << spec.name << " uses '" << forbidden << "'";
    }
  }
}

// Every program fits the uniform vectors every GLES 2 context offers (128 in the vertex stage, 16 in the fragment
// stage), counted as GLSL ES 1.00's Appendix A packs them (gl/UniformPacking.h): a driver that offers only the
// minimum may refuse to link a program that needs more. The forward lighting with the punctual lights a 16-vector
// context gets (none); its other light counts against LightingEffect.h's figures.
TEST(Shaders, EveryProgramFitsTheGles2UniformVectors) {
  const gl::GlCaps& caps = test::context().caps();
  auto buildable = [&](const ProgramSpec& spec) {
    return std::all_of(spec.extensions.begin(), spec.extensions.end(), [&](const std::string& e) { return caps.has(e); });
  };
  auto rowsOf = [](const ProgramSpec& spec) {
    const gl::Program program = spec.build();
    const gl::StageUniforms uniforms =
        gl::activeUniformsByStage(program.id(), spec.vertexSource(), spec.fragmentSource());
    return std::make_pair(gl::packedUniformRows(uniforms.vertex), gl::packedUniformRows(uniforms.fragment));
  };
  const int minimumLights = LightingEffect::punctualLightsPerDraw(FragmentLimits::gles2Minimum().uniformVectors);
  EXPECT_EQ(minimumLights, 0);
  std::vector<ProgramSpec> specs;
  // The lighting and the transparent layer size their programs to the context (lights per draw, the transparent
  // layer's fog): at GLES 2's minimum, these.
  for (ProgramSpec& spec : Renderer::allProgramSpecs())
    if (spec.name.rfind("lighting[", 0) != 0 && spec.name.rfind("transparency[", 0) != 0)
      specs.push_back(std::move(spec));
  for (ProgramSpec& spec : LightingEffect::programSpecs(
           minimumLights, LightingEffect::punctualLightsPerDraw(FragmentLimits::gles2Minimum().uniformVectors, true)))
    specs.push_back(std::move(spec));
  const int gles2Vectors = FragmentLimits::gles2Minimum().uniformVectors;
  for (ProgramSpec& spec : TransparencyEffect::programSpecs(gles2Vectors)) specs.push_back(std::move(spec));
  int worstVertex = 0, worstFragment = 0;
  std::string worstVertexName, worstFragmentName;
  for (const ProgramSpec& spec : specs) {
    if (!buildable(spec)) continue;
    const auto [vertex, fragment] = rowsOf(spec);
    EXPECT_LE(vertex, 128) << spec.name;
    EXPECT_LE(fragment, 16) << spec.name;
    if (vertex > worstVertex) std::tie(worstVertex, worstVertexName) = std::make_pair(vertex, spec.name);
    if (fragment > worstFragment) std::tie(worstFragment, worstFragmentName) = std::make_pair(fragment, spec.name);
  }
  std::printf("%zu programs; most vertex vectors %d (%s), most fragment vectors %d (%s); this context offers %d and "
              "%d\n",
              specs.size(), worstVertex, worstVertexName.c_str(), worstFragment, worstFragmentName.c_str(),
              caps.maxVertexUniformVectors, caps.maxFragmentUniformVectors);

  // The forward lighting's heaviest forms (every PBR texture, alpha mask; and the same with the material layers) with
  // the tone-mapping stage fused, with 0 .. 4 lights: exactly the figures punctualLightsPerDraw counts with (the
  // layered ones with kMaterialLayerVectors more).
  for (int lights = 0; lights <= kMaxPunctualLights; ++lights) {
    const std::vector<StageHeadSpec> heads = LightingEffect::stageHeads(lights);
    const ProgramSpec& heaviest = heads[heads.size() - 2].program;
    const ProgramSpec& layered = heads.back().program;
    ASSERT_NE(heaviest.name.find("forward,mask,texture,pbr,atlas"), std::string::npos) << heaviest.name;
    ASSERT_NE(layered.name.find("forward,mask,texture,pbr,layers"), std::string::npos) << layered.name;
    auto fusedRows = [&](const ProgramSpec& head) {
      return rowsOf(fusedProgram(head, {TonemapEffect::stage(ToneMapOperator::AcesFitted)}, ColorSpace::Hdr)).second;
    };
    EXPECT_EQ(fusedRows(heaviest), kForwardLightingVectorsWithoutLights + lights * kVectorsPerPunctualLight)
        << lights << " lights";
    // The layered program's rows leave no spare column for the tone curve's two floats: kMaterialLayerVectors counts
    // that row.
    EXPECT_EQ(fusedRows(layered),
              kForwardLightingVectorsWithoutLights + kMaterialLayerVectors + lights * kVectorsPerPunctualLight)
        << lights << " lights";
  }
  EXPECT_EQ(LightingEffect::punctualLightsPerDraw(16, true), -1);
  EXPECT_EQ(LightingEffect::punctualLightsPerDraw(17, true), 0);
  EXPECT_EQ(LightingEffect::punctualLightsPerDraw(28, true), 3);
  EXPECT_EQ(LightingEffect::punctualLightsPerDraw(29, true), 4);

  // The transparent layer's programs at each budget a context's fragment vectors give (TransparencyEffect::budget):
  // the heaviest fits those vectors, and leaves fewer than 5 spare (a light's 3, and 2 that packing may leave part-
  // filled) unless every light is on. GLSL ES 1.00's packing is not
  // additive (a float of one feature fills a row another left part-empty: the layers take 2 vectors without the fog
  // and 1 with it), so the constants are the dearer figures and the budget is held to fit, not to equal them.
  const int wholeLayer =
      kTransparentVectors + kTransparentFogVectors + kTransparentLayerVectors + kTransparentFilteredVectors + 12;
  for (int vectors = gles2Vectors; vectors <= wholeLayer; ++vectors) {
    const TransparentBudget budget = TransparencyEffect::budget(vectors);
    int most = 0;
    std::string heaviest;
    for (const ProgramSpec& spec : TransparencyEffect::programSpecs(vectors)) {
      const int rows = buildable(spec) ? rowsOf(spec).second : 0;
      if (rows > most) std::tie(most, heaviest) = std::make_pair(rows, spec.name);
    }
    EXPECT_LE(most, vectors) << heaviest;
    EXPECT_LE(most, kTransparentVectors + (budget.fog ? kTransparentFogVectors : 0) +
                        (budget.layers ? kTransparentLayerVectors : 0) +
                        (budget.filtered && !budget.fog ? kTransparentFilteredVectors : 0) + 3 * budget.lights)
        << vectors << " vectors: " << heaviest;
    if (budget.lights < kMaxPunctualLights) {
      EXPECT_LT(vectors - most, 3 + 2) << vectors << " vectors: " << heaviest;
    }
  }
}

// A per-pixel stage fuses into a pass only where its uniforms fit the vectors that pass leaves (frame/Stage.h): each
// head's program with any stage, or a chain of them, takes at most the vectors the head keeps for itself and the
// stages declare, as GLSL ES 1.00 packs them; so what a plan fuses fits the context it was planned for.
TEST(Shaders, FusedStagesTakeNoMoreUniformVectorsThanTheyDeclare) {
  const gl::GlCaps& caps = test::context().caps();
  // Every stage of the table (fog, the tone curve, the display colour's: grading, vignette, grain, dithering).
  std::vector<StageDecl> stages, display;
  for (const EffectEntry& row : effectTable())
    for (const StageDecl& stage : row.stages()) {
      stages.push_back(stage);
      if (stage.inputSpace == ColorSpace::Display) display.push_back(stage);
    }
  std::vector<std::vector<StageDecl>> chains;
  for (const StageDecl& stage : stages) chains.push_back({stage});
  for (const StageDecl& fog : FogEffect::stages())
    chains.push_back({fog, TonemapEffect::stage(ToneMapOperator::AcesFitted)});
  // The tone curve with each display stage after it, and with all of them, the heaviest variant of each.
  const StageDecl tone = TonemapEffect::stage(ToneMapOperator::Neutral);
  for (const StageDecl& stage : display) chains.push_back({tone, stage});
  chains.push_back({FogEffect::stage(FogMode::Exponential, false), tone, GradingEffect::stage(true, true),
                    VignetteEffect::stage(), GrainEffect::stage(), DitherEffect::stage()});
  // Every head of the table (the lighting's without punctual lights, bloom's and depth of field's composites), and
  // the lighting's with the most lights.
  std::vector<StageHeadSpec> heads = LightingEffect::stageHeads(kMaxPunctualLights);
  for (const EffectEntry& row : effectTable())
    for (StageHeadSpec& head : row.stageHeads()) heads.push_back(std::move(head));
  int checked = 0;
  for (const std::vector<StageDecl>& chain : chains) {
    int declared = 0;
    for (const StageDecl& stage : chain) declared += stage.uniformVectors;
    std::vector<std::pair<ProgramSpec, int>> programs = {
        {fusedProgram(stagePassHead(chain), chain, chain.front().inputSpace), kStagePassUniformVectors}};
    for (const StageHeadSpec& head : heads)
      if (head.space == chain.front().inputSpace)
        programs.emplace_back(fusedProgram(head.program, chain, head.space), head.uniformVectors);
    for (const auto& [spec, vectors] : programs) {
      if (!std::all_of(spec.extensions.begin(), spec.extensions.end(),
                       [&](const std::string& e) { return caps.has(e); }))
        continue;
      const gl::Program program = spec.build();
      const gl::StageUniforms uniforms =
          gl::activeUniformsByStage(program.id(), spec.vertexSource(), spec.fragmentSource());
      EXPECT_LE(gl::packedUniformRows(uniforms.fragment), vectors + declared) << spec.name;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
}
