#pragma once
// One triangle covering the viewport (attribute slot 0: a_position, clip-space xy), drawn by every image-space pass
// with shaders_es2/lib/fullscreen.vert. The Renderer owns one and lends it to its effects.
#include "gl/GlObjects.h"

namespace obscura {

class FullscreenTriangle {
 public:
  FullscreenTriangle();
  void draw() const;
  // While withheld, draw() draws nothing: Renderer::prepare runs a frame's passes for the programs they ask for, with
  // stand-ins in their place (ProgramCache::Rehearsal), and a stand-in's draw would only cost the driver time.
  void withholdDraws(bool withheld) { withheld_ = withheld; }

 private:
  gl::BufferHandle vertices_;
  bool withheld_ = false;
};

}  // namespace obscura
