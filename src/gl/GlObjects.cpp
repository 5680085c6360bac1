#include "gl/GlObjects.h"

namespace obscura::gl {
namespace {
LiveObjects g_live;
std::uint32_t g_generation = 0;
}  // namespace

const LiveObjects& liveObjects() { return g_live; }

void abandonContextObjects() { ++g_generation; }
std::uint32_t contextGeneration() { return g_generation; }

namespace detail {
namespace {
// A name from glGen* (`generate`), counted in `live`; and its glDelete* (`remove`) where the name is still the
// context's. The entry points are passed as called: natively they are pointers the current context filled in.
template <typename Generate>
GLuint generated(Generate generate, int& live) {
  GLuint id = 0;
  generate(1, &id);
  ++live;
  return id;
}
template <typename Remove>
void removed(Remove remove, GLuint id, bool deleteName, int& live) {
  if (deleteName) remove(1, &id);
  --live;
}
}  // namespace

GLuint TextureKind::create() { return generated(glGenTextures, g_live.textures); }
void TextureKind::destroy(GLuint id, bool deleteName) { removed(glDeleteTextures, id, deleteName, g_live.textures); }
GLuint BufferKind::create() { return generated(glGenBuffers, g_live.buffers); }
void BufferKind::destroy(GLuint id, bool deleteName) { removed(glDeleteBuffers, id, deleteName, g_live.buffers); }
GLuint FramebufferKind::create() { return generated(glGenFramebuffers, g_live.framebuffers); }
void FramebufferKind::destroy(GLuint id, bool deleteName) {
  removed(glDeleteFramebuffers, id, deleteName, g_live.framebuffers);
}
GLuint RenderbufferKind::create() { return generated(glGenRenderbuffers, g_live.renderbuffers); }
void RenderbufferKind::destroy(GLuint id, bool deleteName) {
  removed(glDeleteRenderbuffers, id, deleteName, g_live.renderbuffers);
}
GLuint VertexArrayKind::create() { return generated(glGenVertexArraysOES, g_live.vertexArrays); }
void VertexArrayKind::destroy(GLuint id, bool deleteName) {
  removed(glDeleteVertexArraysOES, id, deleteName, g_live.vertexArrays);
}
}  // namespace detail

ShaderHandle::ShaderHandle(GLenum stage) : id_(glCreateShader(stage)) {
  if (id_ != 0) ++g_live.shaders;
}
ShaderHandle::~ShaderHandle() {
  if (id_ != 0) {
    if (generation_ == contextGeneration()) glDeleteShader(id_);
    --g_live.shaders;
  }
}
ShaderHandle& ShaderHandle::operator=(ShaderHandle&& other) noexcept {
  if (this != &other) {
    ShaderHandle old(std::move(*this));
    id_ = std::exchange(other.id_, 0);
    generation_ = other.generation_;
  }
  return *this;
}

ProgramHandle ProgramHandle::create() {
  const GLuint id = glCreateProgram();
  if (id != 0) ++g_live.programs;
  return ProgramHandle(id);
}
ProgramHandle::~ProgramHandle() {
  if (id_ != 0) {
    if (generation_ == contextGeneration()) glDeleteProgram(id_);
    --g_live.programs;
  }
}
ProgramHandle& ProgramHandle::operator=(ProgramHandle&& other) noexcept {
  if (this != &other) {
    ProgramHandle old(std::move(*this));
    id_ = std::exchange(other.id_, 0);
    generation_ = other.generation_;
  }
  return *this;
}

}  // namespace obscura::gl
