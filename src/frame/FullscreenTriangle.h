#pragma once
// One triangle covering the viewport (attribute slot 0: a_position, clip-space xy), drawn by every image-space pass
// with shaders_es2/lib/fullscreen.vert. The Renderer owns one and lends it to its effects.
#include "gl/GlObjects.h"

namespace obscura {

class FullscreenTriangle {
 public:
  // `vertexArray`: keep the stream in a vertex array object (OES_vertex_array_object, where the context has it and
  // RendererOptions::allowVertexArrays does not refuse it): a draw is then three WebGL calls (bind it, draw, bind the
  // default object again) instead of six (the buffer, the attribute's array and pointer, and their undoing). The
  // frame draws it once a full-screen pass, 51 times with every effect on.
  explicit FullscreenTriangle(bool vertexArray = false);
  void draw() const;
  // While withheld, draw() draws nothing: Renderer::prepare runs a frame's passes for the programs they ask for, with
  // stand-ins in their place (ProgramCache::Rehearsal), and a stand-in's draw would only cost the driver time.
  void withholdDraws(bool withheld) { withheld_ = withheld; }

 private:
  gl::BufferHandle vertices_;
  gl::VertexArrayHandle vertexArray_;  // none without the extension
  bool withheld_ = false;
};

}  // namespace obscura
