#include "frame/FullscreenTriangle.h"

#include "gl/Program.h"

namespace obscura {

FullscreenTriangle::FullscreenTriangle() : vertices_(gl::BufferHandle::create()) {
  const float corners[6] = {-1.0f, -1.0f, 3.0f, -1.0f, -1.0f, 3.0f};
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.id());
  glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void FullscreenTriangle::draw() const {
  if (withheld_) return;
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.id());
  glEnableVertexAttribArray(gl::kAttribPosition);
  glVertexAttribPointer(gl::kAttribPosition, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisableVertexAttribArray(gl::kAttribPosition);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

}  // namespace obscura
