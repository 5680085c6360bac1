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
GLuint TextureKind::create() {
  GLuint id = 0;
  glGenTextures(1, &id);
  ++g_live.textures;
  return id;
}
void TextureKind::destroy(GLuint id, bool deleteName) {
  if (deleteName) glDeleteTextures(1, &id);
  --g_live.textures;
}
GLuint BufferKind::create() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  ++g_live.buffers;
  return id;
}
void BufferKind::destroy(GLuint id, bool deleteName) {
  if (deleteName) glDeleteBuffers(1, &id);
  --g_live.buffers;
}
GLuint FramebufferKind::create() {
  GLuint id = 0;
  glGenFramebuffers(1, &id);
  ++g_live.framebuffers;
  return id;
}
void FramebufferKind::destroy(GLuint id, bool deleteName) {
  if (deleteName) glDeleteFramebuffers(1, &id);
  --g_live.framebuffers;
}
GLuint RenderbufferKind::create() {
  GLuint id = 0;
  glGenRenderbuffers(1, &id);
  ++g_live.renderbuffers;
  return id;
}
void RenderbufferKind::destroy(GLuint id, bool deleteName) {
  if (deleteName) glDeleteRenderbuffers(1, &id);
  --g_live.renderbuffers;
}
GLuint VertexArrayKind::create() {
  GLuint id = 0;
  glGenVertexArraysOES(1, &id);
  ++g_live.vertexArrays;
  return id;
}
void VertexArrayKind::destroy(GLuint id, bool deleteName) {
  if (deleteName) glDeleteVertexArraysOES(1, &id);
  --g_live.vertexArrays;
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
