#pragma once
// The baseline GL state every pass starts from and returns to, so no state leaks from one pass into the next:
// depth test off with writes on, face culling off with CCW front faces, blending off (func ONE, ZERO), scissor test,
// polygon offset and stencil test off, no program, buffers, textures (units 0..7, and 8 where the context has a
// ninth) or vertex attribute arrays (slots 0..7) bound, texture unit 0 active, the default vertex array object bound
// (where OES_vertex_array_object exists). Framebuffer and viewport are not part
// of it: each pass binds its own target. With checkGlErrors, the Renderer checks it after every pass.
#include <string>

namespace obscura::gl {

void restoreBaselineState();
// Empty when the current state is the baseline; otherwise a list of what differs (used by tests).
std::string baselineStateDifferences();
// Whether the current context has vertex array objects (GlCaps::query says so): the baseline then also has the
// default one bound, which baselineStateDifferences can only ask where the extension exists.
void setVertexArraysInBaseline(bool present);

}  // namespace obscura::gl
