#pragma once
// Small RAII owners for raw GL object names. Each GL object has exactly one owner; owners move, never copy.
#include <cstdint>
#include <utility>

#include "gl/GlApi.h"

namespace obscura::gl {

// Number of GL objects currently owned by these wrappers, per kind. Tests use it to check that a scene reload or a
// context loss returns to the same baseline (nothing leaks, nothing is freed twice).
struct LiveObjects {
  int textures = 0, buffers = 0, framebuffers = 0, renderbuffers = 0, shaders = 0, programs = 0, vertexArrays = 0;
  int total() const { return textures + buffers + framebuffers + renderbuffers + shaders + programs + vertexArrays; }
};
const LiveObjects& liveObjects();

// Context loss (WebGL's webglcontextlost): every name created so far belongs to a context that is gone, and the
// context that replaces it hands out names afresh, possibly the same numbers for new objects. After this call,
// destroying an owner created before it forgets the name instead of passing it to glDelete*, while the live counters
// still go down, so the owners can be dropped in any order and a rebuild checked against the same baseline.
void abandonContextObjects();
// Counts abandonContextObjects() calls. Each owner remembers the value it was created under; owners of names these
// wrappers do not cover (timer queries) do the same.
std::uint32_t contextGeneration();

namespace detail {
// `deleteName` is false for names of an abandoned context: only the counter changes.
struct TextureKind { static GLuint create(); static void destroy(GLuint, bool deleteName); };
struct BufferKind { static GLuint create(); static void destroy(GLuint, bool deleteName); };
struct FramebufferKind { static GLuint create(); static void destroy(GLuint, bool deleteName); };
struct RenderbufferKind { static GLuint create(); static void destroy(GLuint, bool deleteName); };
// OES_vertex_array_object: only where GlCaps::vertexArrayObject says the context has it.
struct VertexArrayKind { static GLuint create(); static void destroy(GLuint, bool deleteName); };
}  // namespace detail

// A move-only owner of one GL name created by Kind::create() and deleted by Kind::destroy().
template <typename Kind>
class Handle {
 public:
  Handle() = default;
  static Handle create() { return Handle(Kind::create()); }
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)), generation_(other.generation_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
      generation_ = other.generation_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_ != 0) Kind::destroy(std::exchange(id_, 0), generation_ == contextGeneration());
  }

 private:
  explicit Handle(GLuint id) : id_(id), generation_(contextGeneration()) {}
  GLuint id_ = 0;
  std::uint32_t generation_ = 0;
};

using TextureHandle = Handle<detail::TextureKind>;
using BufferHandle = Handle<detail::BufferKind>;
using FramebufferHandle = Handle<detail::FramebufferKind>;
using RenderbufferHandle = Handle<detail::RenderbufferKind>;
using VertexArrayHandle = Handle<detail::VertexArrayKind>;

// Shader and program objects are created with arguments, so they get their own small owners.
class ShaderHandle {
 public:
  ShaderHandle() = default;
  explicit ShaderHandle(GLenum stage);
  ~ShaderHandle();
  ShaderHandle(ShaderHandle&& other) noexcept : id_(std::exchange(other.id_, 0)), generation_(other.generation_) {}
  ShaderHandle& operator=(ShaderHandle&& other) noexcept;
  ShaderHandle(const ShaderHandle&) = delete;
  ShaderHandle& operator=(const ShaderHandle&) = delete;
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
  std::uint32_t generation_ = contextGeneration();
};

class ProgramHandle {
 public:
  ProgramHandle() = default;
  static ProgramHandle create();
  ~ProgramHandle();
  ProgramHandle(ProgramHandle&& other) noexcept : id_(std::exchange(other.id_, 0)), generation_(other.generation_) {}
  ProgramHandle& operator=(ProgramHandle&& other) noexcept;
  ProgramHandle(const ProgramHandle&) = delete;
  ProgramHandle& operator=(const ProgramHandle&) = delete;
  GLuint id() const { return id_; }

 private:
  explicit ProgramHandle(GLuint id) : id_(id), generation_(contextGeneration()) {}
  GLuint id_ = 0;
  std::uint32_t generation_ = 0;
};

}  // namespace obscura::gl
