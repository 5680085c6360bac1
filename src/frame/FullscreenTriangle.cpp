#include "frame/FullscreenTriangle.h"

#include "gl/Program.h"

namespace obscura {

FullscreenTriangle::FullscreenTriangle(bool vertexArray) : vertices_(gl::BufferHandle::create()) {
  const float corners[6] = {-1.0f, -1.0f, 3.0f, -1.0f, -1.0f, 3.0f};
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.id());
  glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  if (vertexArray) {
    vertexArray_ = gl::VertexArrayHandle::create();
    glBindVertexArrayOES(vertexArray_.id());
    glEnableVertexAttribArray(gl::kAttribPosition);
    glVertexAttribPointer(gl::kAttribPosition, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindVertexArrayOES(0);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void FullscreenTriangle::draw() const {
  if (withheld_) return;
  if (vertexArray_) {
    glBindVertexArrayOES(vertexArray_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArrayOES(0);
    return;
  }
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.id());
  glEnableVertexAttribArray(gl::kAttribPosition);
  glVertexAttribPointer(gl::kAttribPosition, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisableVertexAttribArray(gl::kAttribPosition);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

}  // namespace obscura
