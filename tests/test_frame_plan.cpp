// The effect table and the frame plan, without GL: the table's order and names, and how a frame's passes are resolved
// (reads bind to earlier writes, unneeded passes are dropped, the result goes into the output, pooled targets are
// reused, a read without a writer is refused with a message naming it).
#include <algorithm>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "base/Error.h"
#include "frame/FramePlan.h"
#include "renderer/EffectTable.h"
#include "renderer/RenderSettings.h"

using namespace obscura;

namespace {

// Targets the synthetic passes below may write, as effects declare them.
std::map<std::string, TargetInfo> targets() {
  std::map<std::string, TargetInfo> out;
  for (const char* name : {"gbuffer", "a", "b", "c", "color", "display-color"})
    out[name] = TargetInfo{name, "test", name == std::string("display-color") ? GLenum(GL_LINEAR) : GLenum(GL_NEAREST),
                           {}};
  return out;
}

PassDecl pass(const std::string& name, std::vector<std::string> reads, std::vector<std::string> writes,
              std::vector<std::string> optionalReads = {}) {
  PassDecl p;
  p.name = name;
  p.reads = std::move(reads);
  p.optionalReads = std::move(optionalReads);
  for (const std::string& w : writes) p.writes.push_back({w, TargetSize::full(), PassDecl::Write::Depth::None, ""});
  p.run = [](PassContext&) {};
  return p;
}

PassDecl present() { return pass("present", {kFinalImageTarget}, {kOutputTarget}); }

std::vector<std::string> running(const FramePlan& plan) {
  std::vector<std::string> out;
  for (const PlannedPass& p : plan.passes())
    if (p.live) out.push_back(p.decl.name);
  return out;
}

const TargetVersion& written(const FramePlan& plan, const std::string& passName, const std::string& target) {
  for (const PlannedPass& p : plan.passes())
    if (p.decl.name == passName) return plan.versions()[static_cast<size_t>(p.writes.at(target))];
  throw std::runtime_error("no pass " + passName);
}

struct Fixture {
  RenderSettings settings;
  FrameContext frame;
  std::map<std::string, TargetInfo> infos = targets();
  FramePlanner planner{settings, frame, infos};
};

}  // namespace

TEST(EffectTable, ListsTheFrameInOrderWithUniqueNames) {
  // The order the frame relies on (docs/architecture.md, "The frame as a table"), whatever rows come between: the
  // G-buffer, then what reads it, the HDR colour's effects up to the tone curve, then the display colour's, FXAA last
  // of those named here. An effect added to the table needs no line here.
  std::vector<std::string> effects;
  for (const EffectEntry& row : effectTable()) effects.push_back(row.info.name);
  auto at = [&](const char* name) { return std::find(effects.begin(), effects.end(), name) - effects.begin(); };
  const std::vector<const char*> order = {"gbuffer", "velocity",     "ao",  "lighting", "lines",
                                          "fog",     "transparency", "taa", "bloom",    "dof",
                                          "tonemap", "motion-blur",  "fxaa", "resolution"};
  for (size_t i = 0; i < order.size(); ++i) {
    ASSERT_LT(at(order[i]), static_cast<long>(effects.size())) << order[i] << " is not in the table";
    if (i > 0) {
      EXPECT_LT(at(order[i - 1]), at(order[i])) << order[i - 1] << " before " << order[i];
    }
  }
  EXPECT_EQ(effects.front(), "gbuffer");
  // The passes: the pose first, the frame's own last, the passes that carry the colour in the frame's order between;
  // no name twice (timers and stats key on them).
  const std::vector<std::string>& passes = framePassNames();
  ASSERT_GE(passes.size(), 3u);
  EXPECT_EQ(passes.front(), "pose");
  EXPECT_EQ(std::vector<std::string>(passes.end() - 2, passes.end()), (std::vector<std::string>{"view", "present"}));
  auto pass = [&](const char* name) { return std::find(passes.begin(), passes.end(), name) - passes.begin(); };
  const std::vector<const char*> passOrder = {"gbuffer", "peel",          "hierarchy", "sao",   "lighting",
                                              "fog",     "taa",           "bloom",     "dof-composite", "tonemap",
                                              "edges",   "motion-blur",   "fxaa",      "upscale"};
  for (size_t i = 1; i < passOrder.size(); ++i) {
    EXPECT_LT(pass(passOrder[i - 1]), pass(passOrder[i])) << passOrder[i];
  }
  EXPECT_LT(pass("fxaa"), static_cast<long>(passes.size()));
  std::set<std::string> unique(passes.begin(), passes.end());
  EXPECT_EQ(unique.size(), passes.size()) << "a pass name twice";
  std::set<std::string> uniqueEffects(effects.begin(), effects.end());
  EXPECT_EQ(uniqueEffects.size(), effects.size()) << "an effect name twice";
  // Every target an effect declares is RGBA8 data with a documented encoding; packed data is never filtered (plain
  // colours may be: the display colour, depth of field's premultiplied half-size fields).
  for (const TargetInfo& target : frameTargets()) {
    EXPECT_FALSE(target.encoding.empty()) << target.name;
    if (target.name != "display-color" && target.name != "dof-near" && target.name != "dof-far") {
      EXPECT_EQ(target.filter, GLenum(GL_NEAREST)) << target.name;
    }
  }
  // The views: the final image, split screen, then every target's, the old views among them.
  const std::vector<std::string>& views = frameViewNames();
  for (const char* view : {"final", "split", "ao", "ao-raw", "normals", "depth", "mask", "scene-color",
                           "display-color", "shading-count"})
    EXPECT_NE(std::find(views.begin(), views.end(), view), views.end()) << view;
  // Switches and parameters follow the names: "ao", "ao.radius", ...
  for (const EffectEntry& row : effectTable())
    for (const ParameterBinding& p : row.parameters)
      EXPECT_TRUE(p.info.name == row.info.name || p.info.name.rfind(row.info.name + ".", 0) == 0) << p.info.name;
}

TEST(TargetSize, SizesAreRelativeToTheFrame) {
  const glm::ivec2 frame(1281, 721);
  EXPECT_EQ(TargetSize::full().of(frame), frame);
  EXPECT_EQ(TargetSize::half().of(frame), glm::ivec2(640, 360));   // floor, as the AO's half resolution
  EXPECT_EQ(TargetSize::quarter().of(frame), glm::ivec2(320, 180));
  EXPECT_EQ(TargetSize::tiles(20).of(frame), glm::ivec2(65, 37));  // ceil: a tile for every pixel
  EXPECT_EQ(TargetSize::quarter().of({2, 3}), glm::ivec2(1, 1));   // never empty
  EXPECT_EQ(TargetSize::tiles(16).name(), "tiles of 16");
}

TEST(FramePlan, ReadsBindToTheLatestEarlierWriteAndTheResultGoesToTheOutput) {
  Fixture f;
  f.planner.add(pass("g", {}, {"gbuffer"}));
  f.planner.add(pass("p1", {"gbuffer"}, {"a"}));
  f.planner.add(pass("p2", {"a"}, {"a"}));  // read-modify-write: a new version, in another target
  f.planner.add(pass("light", {"a"}, {"color"}));
  f.planner.add(pass("tone", {"color"}, {"display-color"}));
  f.planner.add(pass("aa", {"display-color"}, {"display-color"}));
  const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
  EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "p1", "p2", "light", "tone", "aa"}));
  const TargetVersion& a1 = written(plan, "p1", "a");
  const TargetVersion& a2 = written(plan, "p2", "a");
  ASSERT_TRUE(a1.slot && a2.slot);
  EXPECT_FALSE(*a1.slot == *a2.slot) << "a pass never writes the target it reads";
  EXPECT_EQ(plan.passes()[2].reads.at("a"), plan.passes()[1].writes.at("a"));
  EXPECT_TRUE(written(plan, "aa", "display-color").output) << "the last writer of the result draws the output";
  EXPECT_FALSE(written(plan, "tone", "display-color").output);
  EXPECT_FALSE(written(plan, "aa", "display-color").slot);
}

TEST(FramePlan, PooledTargetsAreReusedOnceTheirLastReaderHasRun) {
  Fixture f;
  f.planner.add(pass("p1", {}, {"a"}));
  f.planner.add(pass("p2", {"a"}, {"b"}));
  f.planner.add(pass("p3", {"b"}, {"c"}));  // a is free again here
  f.planner.add(pass("p4", {"c"}, {"display-color"}));
  f.planner.add(pass("p5", {"display-color"}, {"display-color"}));
  const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
  EXPECT_TRUE(*written(plan, "p1", "a").slot == *written(plan, "p3", "c").slot);
  EXPECT_FALSE(*written(plan, "p2", "b").slot == *written(plan, "p3", "c").slot);
  // Three named full-size NEAREST targets in two pooled ones, and one LINEAR (its filter is part of the key).
  EXPECT_EQ(plan.slots().size(), 3u);
}

TEST(FramePlan, PassesWhoseResultsNobodyNeedsDoNotRun) {
  Fixture f;
  f.planner.add(pass("g", {}, {"gbuffer"}));
  f.planner.add(pass("ao", {"gbuffer"}, {"a"}));
  f.planner.add(pass("light", {"a"}, {"color"}, {"gbuffer"}));
  f.planner.add(pass("tone", {"color"}, {"display-color"}));
  f.planner.add(pass("view", {"a"}, {kOutputTarget}));  // a debug view of "a"
  const FramePlan plan = FramePlan::resolve(std::move(f.planner), kOutputTarget, present);
  EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "ao", "view"}));
}

TEST(FramePlan, OptionalReadsNeverKeepAWriterAliveAndSharedDepthFallsBackToItsOwn) {
  PassDecl gbuffer = pass("g", {}, {});
  gbuffer.writes = {{"gbuffer", TargetSize::full(), PassDecl::Write::Depth::Own, ""}};
  Fixture f;
  f.planner.add(gbuffer);
  PassDecl light = pass("light", {}, {}, {"gbuffer"});
  light.writes = {{"color", TargetSize::full(), PassDecl::Write::Depth::Shared, "gbuffer"}};
  f.planner.add(light);
  f.planner.add(pass("tone", {"color"}, {"display-color"}));
  const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
  EXPECT_EQ(running(plan), (std::vector<std::string>{"light", "tone"})) << "nothing needs the G-buffer itself";
  EXPECT_EQ(plan.passes()[1].reads.count("gbuffer"), 0u);
  EXPECT_EQ(written(plan, "light", "color").depth, PassDecl::Write::Depth::Own);

  Fixture g;  // the same, with a pass that needs the G-buffer: the depth is shared
  g.planner.add(gbuffer);
  g.planner.add(pass("ao", {"gbuffer"}, {"a"}));
  PassDecl lit = light;
  lit.reads = {"a"};
  g.planner.add(lit);
  g.planner.add(pass("tone", {"color"}, {"display-color"}));
  const FramePlan shared = FramePlan::resolve(std::move(g.planner), kFinalImageTarget, present);
  EXPECT_EQ(running(shared), (std::vector<std::string>{"g", "ao", "light", "tone"}));
  const TargetVersion& color = written(shared, "light", "color");
  EXPECT_EQ(color.depth, PassDecl::Write::Depth::Shared);
  EXPECT_EQ(shared.versions()[static_cast<size_t>(color.depthVersion)].target, "gbuffer");
}

TEST(FramePlan, ARetainedOrReadResultIsCopiedToTheOutputByThePresentPass) {
  Fixture f;
  f.planner.add(pass("tone", {}, {"display-color"}));
  const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present, {"display-color"});
  EXPECT_EQ(running(plan), (std::vector<std::string>{"tone", "present"}));
  EXPECT_FALSE(written(plan, "tone", "display-color").output);
  EXPECT_EQ(plan.retainedVersion("display-color"), plan.passes()[0].writes.at("display-color"));
  EXPECT_GT(plan.versions()[static_cast<size_t>(plan.retainedVersion("display-color"))].lastReader, 1);
}

TEST(FramePlan, AliasesReadTheTargetTheyStandFor) {
  Fixture f;
  f.planner.add(pass("sao", {}, {"a"}));
  f.planner.alias("b", "a");  // no blur: "b" is the raw "a"
  f.planner.add(pass("light", {"b"}, {"display-color"}));
  const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
  EXPECT_EQ(running(plan), (std::vector<std::string>{"sao", "light"}));
  EXPECT_EQ(plan.passes()[1].reads.at("b"), plan.passes()[0].writes.at("a"));
}

namespace {
// A lighting pass with a deferred form, taken when the G-buffer pass writes the base colour (several render
// targets); both forms take per-pixel stages, the declared (forward) one without drawing into the output.
PassDecl lightingWithAlternatives(int vectors = 16) {
  PassDecl light = pass("light", {"a"}, {"color"});
  light.stageHead = StageHead{"color", ColorSpace::Hdr, vectors, false};
  PassDecl::Alternative deferred;
  deferred.whenWritten = {"b"};
  deferred.reads = {"a", "b"};
  deferred.writes = {{"color", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  deferred.run = [](PassContext&) {};
  deferred.stageHead = StageHead{"color", ColorSpace::Hdr, vectors, true};
  light.alternatives = {deferred};
  return light;
}

// A per-pixel stage pass: `name` maps `input` into `output` (the tone curve maps HDR to display colour), reading
// `also` at its pixel; it takes stages after it itself (as frame/Stage.h's stagePass does).
PassDecl stage(const std::string& name, const std::string& input, const std::string& output,
               std::vector<std::string> also = {}, int vectors = 1) {
  PassDecl p = pass(name, {input}, {output});
  p.reads.insert(p.reads.end(), also.begin(), also.end());
  StageDecl decl;
  decl.name = name;
  decl.input = input;
  decl.outputSpace = output == kFinalImageTarget ? ColorSpace::Display : ColorSpace::Hdr;
  decl.uniformVectors = vectors;
  p.stage = decl;
  p.stageHead = StageHead{output, decl.outputSpace, 16, true};
  return p;
}
}  // namespace

TEST(FramePlan, AlternativesAreTakenOnlyWhereTheirConditionsHold) {
  {  // The base colour is written by a running pass: the deferred form, with its reads.
    Fixture f;
    f.planner.add(pass("g", {}, {"a", "b"}));
    f.planner.add(lightingWithAlternatives());
    f.planner.add(pass("bloom", {"color"}, {"c"}));
    f.planner.add(pass("tone", {"color", "c"}, {"display-color"}));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(plan.passes()[1].reads.count("b"), 1u);
    EXPECT_EQ(plan.passes()[1].reads.at("b"), plan.passes()[0].writes.at("b"));
    EXPECT_TRUE(plan.passes()[1].decl.stageHead->mayWriteOutput) << "the deferred form's offer";
  }
  {  // Declared but not written by a running pass: the forward form.
    Fixture f;
    f.planner.add(pass("g", {}, {"a"}));
    f.planner.add(pass("unused", {}, {"b"}));
    f.planner.add(lightingWithAlternatives());
    f.planner.add(pass("bloom", {"color"}, {"c"}));
    f.planner.add(pass("tone", {"color", "c"}, {"display-color"}));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "bloom", "tone"}));
    EXPECT_EQ(plan.passes()[2].reads.count("b"), 0u);
    EXPECT_FALSE(plan.passes()[2].decl.stageHead->mayWriteOutput);
  }
}

TEST(FramePlan, PerPixelStagesFuseIntoThePassBeforeThem) {
  {  // Fog and the tone curve after the deferred lighting: one pass, drawing the output, reading what fog reads.
    Fixture f;
    f.planner.add(pass("g", {}, {"gbuffer", "a", "b"}));
    f.planner.add(lightingWithAlternatives());
    f.planner.add(stage("fog", "color", "color", {"gbuffer"}));
    f.planner.add(stage("tone", "color", "display-color"));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light"}));
    const PlannedPass& light = plan.passes()[1];
    EXPECT_EQ(light.absorbed, (std::vector<std::string>{"fog", "tone"}));
    ASSERT_EQ(light.stages.size(), 2u);
    EXPECT_EQ(light.stages[0].name, "fog");
    EXPECT_EQ(light.stageOutput, "display-color");
    EXPECT_EQ(light.reads.at("gbuffer"), plan.passes()[0].writes.at("gbuffer")) << "fog's read, now the light's";
    EXPECT_TRUE(written(plan, "tone", "display-color").output) << "the version, now the lighting's, drawn there";
    EXPECT_EQ(written(plan, "tone", "display-color").writer, 1);
    EXPECT_EQ(light.writes.count("color"), 0u) << "no HDR colour is stored between them";
  }
  {  // The forward form cannot draw into the output: the last stage runs alone (it writes the result).
    Fixture f;
    f.planner.add(pass("g", {}, {"gbuffer", "a"}));
    f.planner.add(lightingWithAlternatives());
    f.planner.add(stage("fog", "color", "color", {"gbuffer"}));
    f.planner.add(stage("tone", "color", "display-color"));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "tone"}));
    EXPECT_EQ(plan.passes()[1].absorbed, std::vector<std::string>{"fog"});
  }
  {  // ... and can where a later pass reads the display colour (FXAA): all in one pass.
    Fixture f;
    f.planner.add(pass("g", {}, {"gbuffer", "a"}));
    f.planner.add(lightingWithAlternatives());
    f.planner.add(stage("fog", "color", "color", {"gbuffer"}));
    f.planner.add(stage("tone", "color", "display-color"));
    f.planner.add(pass("aa", {"display-color"}, {"display-color"}));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "aa"}));
    EXPECT_EQ(plan.passes()[4].reads.at("display-color"), plan.passes()[1].writes.at("display-color"));
  }
  {  // A pass between them that reads the colour (bloom): fog fuses into the lighting, the tone curve runs alone.
    Fixture f;
    f.planner.add(pass("g", {}, {"gbuffer", "a", "b"}));
    f.planner.add(lightingWithAlternatives());
    f.planner.add(stage("fog", "color", "color", {"gbuffer"}));
    f.planner.add(pass("bloom", {"color"}, {"color"}));
    f.planner.add(stage("tone", "color", "display-color"));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "bloom", "tone"}));
    EXPECT_EQ(plan.passes()[1].absorbed, std::vector<std::string>{"fog"});
  }
  {  // A colour someone else reads too (a retained one, a view of it) is kept: no fusion.
    Fixture f;
    f.planner.add(pass("g", {}, {"gbuffer", "a", "b"}));
    f.planner.add(lightingWithAlternatives());
    f.planner.add(stage("tone", "color", "display-color"));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present, {"color"});
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "tone"}));
  }
  {  // A stage that reads what a pass after the head writes cannot run inside the head.
    Fixture f;
    f.planner.add(pass("g", {}, {"a", "b"}));
    f.planner.add(lightingWithAlternatives());
    f.planner.add(pass("edges", {"a"}, {"c"}));
    f.planner.add(stage("lines", "color", "color", {"c"}));
    f.planner.add(stage("tone", "color", "display-color"));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "edges", "lines"}));
    EXPECT_EQ(plan.passes()[3].absorbed, std::vector<std::string>{"tone"}) << "the stage pass takes the next stage";
  }
  {  // Stages fuse only within the fragment uniform vectors the head has left.
    Fixture f;
    f.planner.add(pass("g", {}, {"gbuffer", "a", "b"}));
    f.planner.add(lightingWithAlternatives(2));
    f.planner.add(stage("fog", "color", "color", {"gbuffer"}, 2));
    f.planner.add(stage("tone", "color", "display-color", {}, 1));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "tone"}));
  }
}

TEST(FramePlan, MistakesAreRefusedWithMessagesNamingThem) {
  auto refused = [](const std::function<void(FramePlanner&)>& build, const std::string& expect) {
    Fixture f;
    f.planner.beginEffect("tonemap");
    try {
      build(f.planner);
      FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
      ADD_FAILURE() << "accepted; expected: " << expect;
    } catch (const PipelineError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  };
  refused([](FramePlanner& p) { p.add(pass("tone", {"color"}, {"display-color"})); },
          "pass 'tone' of effect 'tonemap' reads 'color', which no earlier pass writes");
  refused([](FramePlanner& p) { p.add(pass("tone", {}, {"nowhere"})); },
          "pass 'tone' of effect 'tonemap' writes 'nowhere', which its effect does not declare");
  refused([](FramePlanner& p) { p.add(pass("tone", {}, {"a"})); }, "no pass writes the frame's result");
  refused([](FramePlanner& p) { p.alias("b", "a"); }, "makes 'b' an alias of 'a', which no earlier pass writes");
  refused([](FramePlanner& p) { p.add(pass("", {}, {"display-color"})); }, "adds a pass without a name");
  refused(
      [](FramePlanner& p) {
        p.add(pass("g", {}, {"gbuffer"}));
        PassDecl light = pass("light", {"gbuffer"}, {});
        light.writes = {{"display-color", TargetSize::full(), PassDecl::Write::Depth::Shared, "gbuffer"}};
        p.add(light);
      },
      "pass 'light' of effect 'tonemap' shares the depth of 'gbuffer', which has none");
}
