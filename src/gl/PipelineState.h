#pragma once
// The baseline GL state every pass starts from and returns to, so no state leaks from one pass into the next:
// depth test off with writes on, face culling off with CCW front faces, blending off (func ONE, ZERO), scissor test,
// polygon offset and stencil test off, no program, buffers, textures (units 0..7, and 8 and 9 where the context has
// them) or vertex attribute arrays (slots 0..7) bound, texture unit 0 active, the default vertex array object bound
// (where OES_vertex_array_object exists). Framebuffer and viewport are not part
// of it: each pass binds its own target. With checkGlErrors, the Renderer checks it after every pass.
#include <initializer_list>
#include <string>

namespace obscura::gl {

void restoreBaselineState();
// Unbinds the 2D textures of these units, unit 0 active after: a pass that knows what it bound puts back that much,
// where the whole baseline would cost about 45 calls (a WebGL call costs about a microsecond of the page's host time).
void unbindTextureUnits(std::initializer_list<int> units);
// Empty when the current state is the baseline; otherwise a list of what differs (used by tests).
std::string baselineStateDifferences();
// What the current context has (GlCaps::query says so): vertex array objects (the baseline then also has the default
// one bound, which baselineStateDifferences can only ask where the extension exists), and its combined texture
// units (the units the baseline unbinds: at most 10).
void setBaselineContext(bool vertexArrays, int combinedTextureUnits);

}  // namespace obscura::gl
