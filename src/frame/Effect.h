#pragma once
// One effect of the frame: a row of the effect table (renderer/EffectTable.cpp), which lists them in the order they
// run.
//
// An effect has a name (its switch, and the prefix of its parameters: "ao", "ao.radius"), a settings struct, one or
// more passes, and the named targets those passes write. Each frame the Renderer asks every effect that is on to
// plan its passes (Effect::plan): each pass names the targets it reads and writes, and gives the code that draws it.
// The frame plan (frame/FramePlan.h) then checks that every read has an earlier writer, drops passes whose results
// nobody needs (a debug view of the AO runs no lighting), sends the frame's result straight into the output
// framebuffer, and lends each pass a physical RGBA8 target from the pool (frame/RenderTargetPool.h), reusing one
// whose contents are no longer needed.
//
// docs/architecture.md walks through adding an effect.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "gl/GlApi.h"

namespace obscura {

class FramePlanner;
class FrameSettings;
class PassContext;
namespace gl {
class Program;
}

// A target's size relative to the frame (the output size). Half and quarter are floor(size / 2^k), at least 1 pixel
// (SaoKernel::hierarchyLevelSize), and so is a scaled size, with its own k along x and y (bloom's chain); tiles are
// ceil(size / tile), one texel per tile x tile pixels; tile columns are ceil(width / tile) by the full height, one
// texel per tile x 1 pixels (the first half of a separable tile pass). A fixed size does not follow the frame (auto
// exposure's 1 x 1 result and its 128-bin histogram).
struct TargetSize {
  enum class Kind { Full, Half, Quarter, Tiles, TileColumns, Scaled, Fixed };
  Kind kind = Kind::Full;
  int tile = 0;                // Tiles and TileColumns; Fixed: the width
  int height = 0;              // Fixed only
  int shiftX = 0, shiftY = 0;  // Scaled only: floor(width / 2^shiftX) x floor(height / 2^shiftY)
  int timesX = 1, plusX = 0, plusY = 0;  // Scaled only: that width times timesX plus plusX, that height plus plusY

  static TargetSize full() { return {Kind::Full, 0}; }
  static TargetSize half() { return {Kind::Half, 0}; }
  static TargetSize quarter() { return {Kind::Quarter, 0}; }
  static TargetSize tiles(int tile) { return {Kind::Tiles, tile}; }
  static TargetSize tileColumns(int tile) { return {Kind::TileColumns, tile}; }
  static TargetSize scaled(int shiftX, int shiftY) { return {Kind::Scaled, 0, 0, shiftX, shiftY}; }
  static TargetSize fixed(int width, int height) { return {Kind::Fixed, width, height}; }
  // A Scaled size side by side `times` times, with `plusX` more columns and `plusY` more rows (blocks of a grid that
  // reach past the frame's edges: bloom's prefilter).
  TargetSize widened(int times, int moreX, int moreY) const {
    TargetSize s = *this;
    s.timesX = times;
    s.plusX = moreX;
    s.plusY = moreY;
    return s;
  }
  glm::ivec2 of(glm::ivec2 frame) const;
  std::string name() const;  // "full", "half", "quarter", "tiles of 16", "1/4 x 1/8", "128x64"
  bool operator==(const TargetSize& o) const {
    return kind == o.kind && tile == o.tile && height == o.height && shiftX == o.shiftX && shiftY == o.shiftY &&
           timesX == o.timesX && plusX == o.plusX && plusY == o.plusY;
  }
};

// How a debug view (shaders_es2/frame/debug_view.frag) shows a target's bytes: decoded, but otherwise as they are (no
// tone curve, no output encoding, no antialiasing), so tools can read the values back.
enum class ViewDecoding {
  Grey,      // R as grey (AO)
  Normals,   // the G-buffer's octahedral normal, n * 0.5 + 0.5 (background black)
  Depth,     // the G-buffer's 16-bit linear depth as grey (background white)
  Mask,      // geometry white, background black (what obscura-compare measures over)
  HdrColor,  // the HDR encoding of lib/hdr.glsl, decoded, clamped to [0, 1]
  Color,     // RGB as stored
  Count,     // R holds a count / 255: grey 32/255 per count, white from 8 (the lighting's shading count)
  Velocity,  // encoding/VelocityPacking.h decoded: RG = 0.5 + 64 v (v in uv units: white from 1/128 of the screen a
             // frame; grey 0.5 still), B = 0.5
  NormalsFromDepth,  // the normal reconstructed from the G-buffer's depth (lib/normal_from_depth.glsl), as Normals;
                     // where it falls back to the stored normal, black
};

struct TargetView {
  std::string name;  // the --view name
  ViewDecoding decoding;
};

// A named RGBA8 target: what an effect's passes may write, documented once.
struct TargetInfo {
  std::string name;
  std::string encoding;        // what the four bytes hold (docs, the page's view list)
  GLenum filter = GL_NEAREST;  // LINEAR only for colours a reader filters (FXAA); packed data is always NEAREST
  std::vector<TargetView> views;
};

// What an effect is, read by everything that lists effects: the page, the CLI's help, obscura-bench, the timers.
struct EffectInfo {
  std::string name;                 // switch and parameter prefix
  std::string title;                // for people: "Ambient obscurance"
  bool hasSwitch = true;            // false: always part of the frame (the G-buffer, the lighting)
  bool jitters = false;             // on: the projection is jittered per frame (Halton 2, 3; FrameContext)
  std::vector<std::string> passes;  // every pass it may run, in order (timer and stats keys)
  std::vector<TargetInfo> targets;  // every target it may write
  // On: its result depends on earlier frames or on the shutter (motion blur, TAA); references made by brute force
  // switch these off and integrate instead (renderer/AccumulationReference.h). Last, so brace initialisers may omit it.
  bool temporal = false;
  // On: it adds passes of its own over the frame (or, for FXAA, over the output), each a program that SwiftShader
  // compiles at its first draw; quick start's cheap first frame leaves it out (resolution.quick-start,
  // Renderer::quickStartSettings).
  bool waitsForFullFrame = false;
};

// The colour a per-pixel stage reads and writes: linear HDR (before the tone curve: "scene-color") or display
// (sRGB-encoded, after it: "display-color").
enum class ColorSpace { Hdr, Display };

// A per-pixel stage (frame/Stage.h): work that maps one pixel's colour from that pixel's own inputs (its colour, its
// view-space position and normal, its uv) and the frame's constants, such as fog, exposure and the tone curve. Its
// GLSL is a function `vec3 FUNCTION(vec3 color, StagePixel pixel)` in its own file (lib/stage.glsl), which the plan
// puts into whichever program runs the stage: its own pass's, or that of the pass before it it fuses into.
struct StageDecl {
  std::string name;       // its pass's name ("fog"), and its part of a fused program's name
  std::string variant;    // its variant's part of that name ("exp,height": "fog[exp,height]")
  std::string file;       // the GLSL file that defines its function and uniforms ("fog/fog.glsl")
  std::string function;   // "fogStage"
  std::vector<std::pair<std::string, std::string>> defines;  // its variant's, named after it (FOG_MODE)
  std::string input;      // the target whose colour it maps ("scene-color")
  ColorSpace inputSpace = ColorSpace::Hdr, outputSpace = ColorSpace::Hdr;
  bool position = false;  // it reads the pixel's view-space position (fog: the distance)
  bool normal = false;    // it reads the pixel's view-space normal
  // Other targets it reads (sampler, target): a frame constant (auto exposure's 1 x 1 result) or a coarser image
  // read at its pixel's uv (the lens light). A stage with any runs in a head that binds them (its own stage pass), and
  // fuses only after the passes that write them.
  std::vector<std::pair<std::string, std::string>> textures;
  // Textures its own effect holds (grading's LUT), by sampler, asked for when the pass runs: the head binds each to
  // a texture unit it has spare (StageHead::textureUnits), so such a stage fuses only into a head with units left.
  std::vector<std::pair<std::string, std::function<GLuint()>>> ownTextures;
  // The fragment uniform vectors its uniforms take, as GLSL ES 1.00 packs them (Appendix A, section 7): a stage
  // fuses into a pass only where they fit beside that pass's own (Shaders.EveryProgramFitsTheGles2UniformVectors
  // holds the figures).
  int uniformVectors = 0;
  // Sets its uniforms, each frame, on whichever program runs it (in use).
  std::function<void(const gl::Program&, const PassContext&)> uniforms;
  std::string label() const { return variant.empty() ? name : name + "[" + variant + "]"; }
};

// What a pass offers the stages after it: it writes its colour into `color`, in `space`, from a program that calls
// finishPixel (lib/stage.glsl), so a stage that reads that colour next can run in the same program instead of a pass
// of its own (FramePlan.h, rule 4b).
struct StageHead {
  std::string color;
  ColorSpace space = ColorSpace::Hdr;
  int uniformVectors = 0;       // fragment uniform vectors left for stages
  bool mayWriteOutput = true;   // false: it cannot draw into the output framebuffer (it depth-tests)
  bool bindsTextures = false;   // it binds the textures a stage reads (StageDecl::textures): a stage pass does
  int textureUnits = 0;         // units left for the stages' textures (StageDecl::textures and ownTextures)
  int firstTextureUnit = 0;     // where those units start (a head that binds its stages' own textures itself)
  // It depth-tests against the depth it shares with an earlier pass (the forward lighting over the G-buffer's): where
  // that pass runs, it keeps that depth rather than draw into the output with the output's own.
  bool keepsSharedDepth = false;
  // It fills StagePixel's view-space position and normal (STAGE_POSITION, STAGE_NORMAL: the lighting, a stage pass);
  // false: a stage that needs them (fog) does not fuse into it.
  bool pixelGeometry = true;
};

// One pass of this frame: what it reads and writes, and how it draws. Reads of a target bind to its latest earlier
// writer; a pass that reads and writes one target gets a fresh physical target for the new contents (ping-pong).
struct PassDecl {
  struct Write {
    std::string target;
    TargetSize size = TargetSize::full();
    // Depth renderbuffer attached while the pass draws: none, its own (cleared by the pass), or that of a target it
    // reads, shared so the pass can depth-test against what an earlier pass drew. A shared depth whose target is
    // not read this frame falls back to its own.
    enum class Depth { None, Own, Shared } depth = Depth::None;
    std::string depthFrom;  // Shared: the target whose depth renderbuffer it attaches
    // A history target (RenderTargetPool::History, named after the target): the pass writes this frame's side of
    // the pair, which later passes of the frame read by the target's name and the next frame reads as the previous
    // one (PassContext::history). Not pooled; a pass that writes only history is `keep`.
    bool history = false;

    Write() = default;
    // A full-size write of `target` without depth, unless told otherwise.
    Write(std::string target_, TargetSize size_ = TargetSize::full(), Depth depth_ = Depth::None,
          std::string depthFrom_ = "", bool history_ = false)
        : target(std::move(target_)), size(size_), depth(depth_), depthFrom(std::move(depthFrom_)),
          history(history_) {}
    Write(const char* target_) : Write(std::string(target_)) {}  // NOLINT: a target's name is a write of it
  };

  // Another way to run the pass, taken when its conditions hold once the plan knows which passes run (the first of
  // a pass's alternatives that applies wins; none: the pass as declared). It keeps the pass's name.
  struct Alternative {
    // Targets that a running earlier pass writes (not only one that is declared): the deferred lighting needs the
    // base colour the G-buffer pass writes where it has several render targets, and runs.
    std::vector<std::string> whenWritten;
    std::vector<std::string> reads;
    std::vector<Write> writes;  // without `absorbing`: the same targets as the pass's
    std::function<void(PassContext&)> run;
    std::optional<StageHead> stageHead;  // what this form offers the stages after it
    // "" or the name of a pass that is the only running reader of what this pass writes, reads nothing else, and
    // whose own writes are read by a running pass (or, with `mayWriteOutput`, are the frame's result). The
    // alternative then does that pass's work too: it writes that pass's targets (its `writes` name them), and that
    // pass does not run ("done by" this one). For a pass that reads its neighbours, which no stage can fuse: FXAA
    // does the upscale of a frame rendered below the output's size.
    std::string absorbing;
    bool mayWriteOutput = false;
  };

  std::string name;                        // one of its effect's EffectInfo::passes
  std::vector<std::string> reads;          // required: an earlier pass must write each
  std::vector<std::string> optionalReads;  // used when some earlier pass writes it anyway; never keeps one alive
  std::vector<Write> writes;
  bool keep = false;                       // runs even when nothing reads what it writes (history)
  std::function<void(PassContext&)> run;
  // The names of the programs it draws with, as the plan chose them (ProgramSpec::name): the plan's shape for tests
  // and tools; what is drawn is what `run` draws.
  std::vector<std::string> programs;
  std::vector<Alternative> alternatives;
  // A per-pixel stage (frame/Stage.h: stagePass): reads `stage->input` (and, for its position or normal, the
  // G-buffer) at its pixel only and writes one colour target. The plan may run it inside the pass before it.
  std::optional<StageDecl> stage;
  // Stages may fuse into this pass (the lighting; a stage pass, for the stages after it).
  std::optional<StageHead> stageHead;
};

// Effects draw through this during their passes.
class Effect {
 public:
  virtual ~Effect() = default;
  // Makes ready what this frame's settings ask the effect to hold (the lighting's environment): loads it, or keeps
  // what it has. Called every frame for every effect, on or off, in table order, before the plan (which is cached:
  // plan() is not called every frame, and neither loads nor frees).
  virtual void prepare(const FrameSettings& settings) { (void)settings; }
  // Adds this frame's passes (none: the effect has nothing to do with these settings). Called in table order for
  // every effect that is on, and for the effect whose target the frame's debug view shows. Pure: it declares passes
  // from the settings that shape the plan; each pass reads this frame's values from its PassContext when it runs.
  virtual void plan(FramePlanner& planner) = 0;
};

}  // namespace obscura
