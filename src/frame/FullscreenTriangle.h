#pragma once
// One triangle covering the viewport (attribute slot 0: a_position, clip-space xy), drawn by every image-space pass
// with shaders_es2/lib/fullscreen.vert. The Renderer owns one and lends it to its effects.
#include "gl/GlObjects.h"

namespace obscura {

class FullscreenTriangle {
 public:
  FullscreenTriangle();
  void draw() const;

 private:
  gl::BufferHandle vertices_;
};

}  // namespace obscura
