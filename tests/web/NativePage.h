#pragma once
// The browser around the page's C++ side when it runs natively (tests/web/emscripten/emscripten.h): one headless
// context (TestSupport's) stands for every WebGL canvas, and the test plays the browser's part through these calls.
namespace obscura::test::page {

// Runs the requestAnimationFrame callback the module registered, at `milliseconds` (the browser's clock); false
// where none is registered.
bool animationFrame(double milliseconds);
// The canvas's CSS size times devicePixelRatio (default 160 x 90).
void setDisplaySize(int width, int height);
// Fires the canvas's webglcontextlost and webglcontextrestored events, as the browser does (the GL objects stay in
// the headless context: the module must forget them, not delete them).
void loseContext();
void restoreContext();
// Messages the module logged with emscripten_log since the last call.
int loggedErrors();

}  // namespace obscura::test::page
