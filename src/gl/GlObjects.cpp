#include "gl/GlObjects.h"

namespace obscura::gl {
namespace {
LiveObjects g_live;
}

const LiveObjects& liveObjects() { return g_live; }

namespace detail {
GLuint TextureKind::create() {
  GLuint id = 0;
  glGenTextures(1, &id);
  ++g_live.textures;
  return id;
}
void TextureKind::destroy(GLuint id) {
  glDeleteTextures(1, &id);
  --g_live.textures;
}
GLuint BufferKind::create() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  ++g_live.buffers;
  return id;
}
void BufferKind::destroy(GLuint id) {
  glDeleteBuffers(1, &id);
  --g_live.buffers;
}
GLuint FramebufferKind::create() {
  GLuint id = 0;
  glGenFramebuffers(1, &id);
  ++g_live.framebuffers;
  return id;
}
void FramebufferKind::destroy(GLuint id) {
  glDeleteFramebuffers(1, &id);
  --g_live.framebuffers;
}
GLuint RenderbufferKind::create() {
  GLuint id = 0;
  glGenRenderbuffers(1, &id);
  ++g_live.renderbuffers;
  return id;
}
void RenderbufferKind::destroy(GLuint id) {
  glDeleteRenderbuffers(1, &id);
  --g_live.renderbuffers;
}
}  // namespace detail

ShaderHandle::ShaderHandle(GLenum stage) : id_(glCreateShader(stage)) {
  if (id_ != 0) ++g_live.shaders;
}
ShaderHandle::~ShaderHandle() {
  if (id_ != 0) {
    glDeleteShader(id_);
    --g_live.shaders;
  }
}
ShaderHandle& ShaderHandle::operator=(ShaderHandle&& other) noexcept {
  if (this != &other) {
    ShaderHandle old(std::move(*this));
    id_ = std::exchange(other.id_, 0);
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
    glDeleteProgram(id_);
    --g_live.programs;
  }
}
ProgramHandle& ProgramHandle::operator=(ProgramHandle&& other) noexcept {
  if (this != &other) {
    ProgramHandle old(std::move(*this));
    id_ = std::exchange(other.id_, 0);
  }
  return *this;
}

}  // namespace obscura::gl
