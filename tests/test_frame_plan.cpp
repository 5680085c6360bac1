// The effect table and the frame plan, without GL: the table's order and names, and how a frame's passes are resolved
// (reads bind to earlier writes, unneeded passes are dropped, the result goes into the output, pooled targets are
// reused, a read without a writer is refused with a message naming it).
#include <algorithm>
#include <map>

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
  std::vector<std::string> effects;
  for (const EffectEntry& row : effectTable()) effects.push_back(row.info.name);
  EXPECT_EQ(effects, (std::vector<std::string>{"gbuffer", "velocity", "ao", "lighting", "lines", "fog", "transparency",
                                                "taa", "bloom", "lens-flare", "glare", "dof", "auto-exposure",
                                                "tonemap", "edges", "motion-blur", "chromatic-aberration", "fxaa",
                                                "resolution"}));
  EXPECT_EQ(framePassNames(),
            (std::vector<std::string>{"pose", "gbuffer", "base-color", "velocity", "peel", "hierarchy", "sao",
                                      "ao-temporal",
                                      "blur-h", "blur-v", "upsample", "lighting", "shading-count", "lines", "fog",
                                      "transmission-levels", "transparency", "taa", "bloom", "bloom-bright",
                                      "lens-flare", "glare",
                                      "dof-coc", "dof-downsample", "dof-tiles-h", "dof-tiles", "dof-neighbors",
                                      "dof-near", "dof-far", "dof-composite", "exposure-meter",
                                      "exposure-reduce", "exposure-reduce-2",
                                      "exposure-histogram", "exposure-bins", "exposure-adapt", "tonemap",
                                      "edges-detect", "edges-h", "edges",
                                      "motion-tiles-h", "motion-tiles", "motion-neighbors", "motion-blur",
                                      "chromatic-aberration", "fxaa", "upscale",
                                      "view", "present"}));
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
// A lighting pass with the two kinds of alternatives the frame uses: a deferred form, taken when the G-buffer pass
// writes the base colour (several render targets), and one that also applies the tone curve when the tone pass is
// the only reader of its colour.
PassDecl lightingWithAlternatives(bool mayWriteOutput) {
  PassDecl light = pass("light", {"a"}, {"color"});
  PassDecl::Alternative folded;
  folded.absorbing = "tone";
  folded.mayWriteOutput = mayWriteOutput;
  folded.reads = {"a"};
  folded.writes = {{"display-color", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  folded.run = [](PassContext&) {};
  PassDecl::Alternative deferred;
  deferred.whenWritten = {"b"};
  deferred.reads = {"a", "b"};
  deferred.writes = {{"color", TargetSize::full(), PassDecl::Write::Depth::None, ""}};
  deferred.run = [](PassContext&) {};
  light.alternatives = {folded, deferred};
  return light;
}
}  // namespace

TEST(FramePlan, AlternativesAreTakenOnlyWhereTheirConditionsHold) {
  {  // Tone is the only reader of the colour and writes the result: the lighting does its work and draws the output.
    Fixture f;
    f.planner.add(pass("g", {}, {"a"}));
    f.planner.add(lightingWithAlternatives(true));
    f.planner.add(pass("tone", {"color"}, {"display-color"}));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light"}));
    EXPECT_EQ(plan.passes()[1].absorbed, std::vector<std::string>{"tone"});
    EXPECT_TRUE(written(plan, "tone", "display-color").output);  // the version, now the lighting's
    EXPECT_EQ(written(plan, "tone", "display-color").writer, 1);
    EXPECT_EQ(plan.passes()[1].writes.count("color"), 0u);
  }
  {  // The same where the alternative may not draw the output: as declared.
    Fixture f;
    f.planner.add(pass("g", {}, {"a"}));
    f.planner.add(lightingWithAlternatives(false));
    f.planner.add(pass("tone", {"color"}, {"display-color"}));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "tone"}));
    EXPECT_TRUE(plan.passes()[1].absorbed.empty());
  }
  {  // A later pass reads the tone pass's result: the fold is allowed without drawing the output.
    Fixture f;
    f.planner.add(pass("g", {}, {"a"}));
    f.planner.add(lightingWithAlternatives(false));
    f.planner.add(pass("tone", {"color"}, {"display-color"}));
    f.planner.add(pass("aa", {"display-color"}, {"display-color"}));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "aa"}));
    EXPECT_EQ(plan.passes()[3].reads.at("display-color"), plan.passes()[1].writes.at("display-color"));
  }
  {  // Another pass needs the HDR colour (or it is retained): no fold.
    Fixture f;
    f.planner.add(pass("g", {}, {"a"}));
    f.planner.add(lightingWithAlternatives(true));
    f.planner.add(pass("bloom", {"color"}, {"c"}));
    f.planner.add(pass("tone", {"color", "c"}, {"display-color"}));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "bloom", "tone"}));
    Fixture r;
    r.planner.add(pass("g", {}, {"a"}));
    r.planner.add(lightingWithAlternatives(true));
    r.planner.add(pass("tone", {"color"}, {"display-color"}));
    const FramePlan retained = FramePlan::resolve(std::move(r.planner), kFinalImageTarget, present, {"color"});
    EXPECT_EQ(running(retained), (std::vector<std::string>{"g", "light", "tone"}));
  }
  {  // The base colour is written by a running pass: the deferred form, with its reads (the fold is impossible).
    Fixture f;
    f.planner.add(pass("g", {}, {"a", "b"}));
    f.planner.add(lightingWithAlternatives(true));
    f.planner.add(pass("bloom", {"color"}, {"c"}));
    f.planner.add(pass("tone", {"color", "c"}, {"display-color"}));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(plan.passes()[1].reads.count("b"), 1u);
    EXPECT_EQ(plan.passes()[1].reads.at("b"), plan.passes()[0].writes.at("b"));
  }
  {  // Declared but not written by a running pass: the forward form.
    Fixture f;
    f.planner.add(pass("g", {}, {"a"}));
    f.planner.add(pass("unused", {}, {"b"}));
    f.planner.add(lightingWithAlternatives(true));
    f.planner.add(pass("bloom", {"color"}, {"c"}));
    f.planner.add(pass("tone", {"color", "c"}, {"display-color"}));
    const FramePlan plan = FramePlan::resolve(std::move(f.planner), kFinalImageTarget, present);
    EXPECT_EQ(running(plan), (std::vector<std::string>{"g", "light", "bloom", "tone"}));
    EXPECT_EQ(plan.passes()[2].reads.count("b"), 0u);
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
