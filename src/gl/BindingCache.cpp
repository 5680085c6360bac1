// gl/GlApi.h declares the GL types first, then includes gl/BindingCache.h.
#include <algorithm>

#include "gl/GlApi.h"

namespace obscura::gl::bindings {
namespace {

// A binding as wanted and as the context holds it; kUnknown for either means "not known in this scope": not asked
// for yet, or whatever the context had when the scope began.
constexpr GLuint kUnknown = 0xFFFFFFFFu;
struct Binding {
  GLuint wanted = kUnknown;
  GLuint held = kUnknown;
  bool pending() const { return wanted != kUnknown && wanted != held; }
};

// The viewport as wanted and as held, where known.
struct Rectangle {
  GLint x = 0, y = 0;
  GLsizei width = 0, height = 0;
  bool operator==(const Rectangle& o) const { return x == o.x && y == o.y && width == o.width && height == o.height; }
};
struct ViewportBinding {
  Rectangle wanted, held;
  bool wantedKnown = false, heldKnown = false;
  bool pending() const { return wantedKnown && (!heldKnown || !(wanted == held)); }
};

// Units the cache tracks: more than the core uses (gpu/TextureUnits.h: ten at most). A unit past them is bound at
// once, as outside a scope.
constexpr GLuint kTrackedUnits = 16;
constexpr int kTargets = 2;  // TEXTURE_2D, TEXTURE_CUBE_MAP

struct State {
  bool deferring = true;
  int depth = 0;  // DeferredBindings scopes open
  Binding activeUnit;  // as a unit index
  Binding textures[kTrackedUnits][kTargets];
  Binding program, vertexArray;
  ViewportBinding viewport;
  Counts counts;
};
State g_state;

int targetIndex(GLenum target) { return target == GL_TEXTURE_CUBE_MAP ? 1 : 0; }
GLenum targetOf(int index) { return index == 1 ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D; }

void makeHeld(Binding& binding) { binding.held = binding.wanted; }

void makeTextures() {
  State& s = g_state;
  for (GLuint unit = 0; unit < kTrackedUnits; ++unit)
    for (int target = 0; target < kTargets; ++target) {
      Binding& texture = s.textures[unit][target];
      if (!texture.pending()) continue;
      if (s.activeUnit.held != unit) {
        raw::glActiveTexture(GL_TEXTURE0 + unit);
        s.activeUnit.held = unit;
        ++s.counts.made;
      }
      raw::glBindTexture(targetOf(target), texture.wanted);
      makeHeld(texture);
      ++s.counts.made;
    }
  if (s.activeUnit.pending()) {
    raw::glActiveTexture(GL_TEXTURE0 + s.activeUnit.wanted);
    makeHeld(s.activeUnit);
    ++s.counts.made;
  }
}

// Forgets what the context holds and what was asked (a scope's start and end).
void forget() {
  State& s = g_state;
  s.activeUnit = {};
  for (auto& unit : s.textures)
    for (Binding& texture : unit) texture = {};
  s.program = {};
  s.vertexArray = {};
  s.viewport = {};
  g_pending = 0;
}

// Records `value` as wanted; true where that leaves it to be made.
bool want(Binding& binding, GLuint value) {
  binding.wanted = value;
  return binding.pending();
}

// A setter of one binding of kind `kind`: GL's (`raw`) at once outside a scope, recorded within one.
template <typename Raw>
void set(Binding& binding, GLuint value, unsigned kind, Raw raw) {
  State& s = g_state;
  ++s.counts.asked;
  if (s.depth == 0) {
    raw(value);
    ++s.counts.made;
    return;
  }
  if (want(binding, value)) g_pending |= kind;
}

}  // namespace

void makePending(unsigned uses) {
  State& s = g_state;
  const unsigned making = g_pending & uses;
  if ((making & kUsesProgram) && s.program.pending()) {
    raw::glUseProgram(s.program.wanted);
    makeHeld(s.program);
    ++s.counts.made;
  }
  if ((making & kUsesVertexArray) && s.vertexArray.pending()) {
    raw::glBindVertexArrayOES(s.vertexArray.wanted);
    makeHeld(s.vertexArray);
    ++s.counts.made;
  }
  if (making & kUsesTextures) makeTextures();
  if ((making & kUsesViewport) && s.viewport.pending()) {
    const Rectangle& r = s.viewport.wanted;
    raw::glViewport(r.x, r.y, r.width, r.height);
    s.viewport.held = r;
    s.viewport.heldKnown = true;
    ++s.counts.made;
  }
  g_pending &= ~making;
}

void activeTexture(GLenum unit) {
  State& s = g_state;
  ++s.counts.asked;
  const GLuint index = unit - GL_TEXTURE0;
  if (s.depth == 0 || index >= kTrackedUnits) {
    // Untracked: the textures asked for so far first, then this unit at once, and the next bindings to it at once.
    make(kUsesTextures);
    raw::glActiveTexture(unit);
    ++s.counts.made;
    s.activeUnit.wanted = s.activeUnit.held = kUnknown;
    return;
  }
  if (want(s.activeUnit, index)) g_pending |= kUsesTextures;
}

void bindTexture(GLenum target, GLuint texture) {
  State& s = g_state;
  ++s.counts.asked;
  if (s.depth == 0 || s.activeUnit.wanted == kUnknown ||
      (target != GL_TEXTURE_2D && target != GL_TEXTURE_CUBE_MAP)) {
    // The unit is not known (no glActiveTexture yet in this scope): the context's active one, at once. No texture is
    // pending then, so nothing is bound out of order.
    make(kUsesTextures);
    raw::glBindTexture(target, texture);
    ++s.counts.made;
    return;
  }
  if (want(s.textures[s.activeUnit.wanted][targetIndex(target)], texture)) g_pending |= kUsesTextures;
}

void useProgram(GLuint program) { set(g_state.program, program, kUsesProgram, raw::glUseProgram); }

void bindVertexArray(GLuint vertexArray) {
  set(g_state.vertexArray, vertexArray, kUsesVertexArray, raw::glBindVertexArrayOES);
}

void viewport(GLint x, GLint y, GLsizei width, GLsizei height) {
  State& s = g_state;
  ++s.counts.asked;
  if (s.depth == 0) {
    raw::glViewport(x, y, width, height);
    ++s.counts.made;
    return;
  }
  s.viewport.wanted = {x, y, width, height};
  s.viewport.wantedKnown = true;
  if (s.viewport.pending()) g_pending |= kUsesViewport;
}

void deleteTextures(GLsizei count, const GLuint* textures) {
  // Made first, so that GL unbinds what it would have: then every binding of a deleted name is 0, as in GL.
  make(kUsesAll);
  raw::glDeleteTextures(count, textures);
  for (const GLuint* texture = textures; texture != textures + count; ++texture)
    for (auto& unit : g_state.textures)
      for (Binding& binding : unit)
        if (binding.held == *texture) binding.wanted = binding.held = 0;
}

void deleteVertexArrays(GLsizei count, const GLuint* vertexArrays) {
  make(kUsesAll);
  raw::glDeleteVertexArraysOES(count, vertexArrays);
  Binding& bound = g_state.vertexArray;
  if (std::find(vertexArrays, vertexArrays + count, bound.held) != vertexArrays + count)
    bound.wanted = bound.held = 0;
}

Counts counts() { return g_state.counts; }

void setDeferring(bool deferring) { g_state.deferring = deferring; }

}  // namespace obscura::gl::bindings

namespace obscura::gl {

DeferredBindings::DeferredBindings() : defers_(bindings::g_state.deferring) {
  if (defers_ && bindings::g_state.depth++ == 0) bindings::forget();
}

DeferredBindings::~DeferredBindings() {
  if (defers_ && --bindings::g_state.depth == 0) {
    bindings::make(kUsesAll);
    bindings::forget();
  }
}

}  // namespace obscura::gl
