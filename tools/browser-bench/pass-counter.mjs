// How many full-screen passes and geometry passes a renderer's frame runs, counted the same way for every renderer of
// the browser benchmark (Obscura's page, three.js, N8AO, pmndrs/postprocessing) from the WebGL calls it makes:
//   - a draw of one full-screen primitive (drawArrays of 3 vertices, or 4 as a strip or 6 as a list: the triangle or
//     quad every post-processing library draws) is one full-screen pass, and the scissored draws of one that follow
//     it into the same framebuffer are its parts (Obscura's passes draw the background apart around the scene's
//     bounds on screen: docs/architecture.md, "The scene's bounds");
//   - any other draw is part of a geometry pass: a run of such draws that no full-screen draw, framebuffer binding,
//     clear or colour-mask change interrupts is one geometry pass (a depth pre-pass and the shading after it: two).
// installPassCounter(gl) wraps the context's methods (the renderers look them up on the context at each call) and
// returns nothing; window.benchPasses.reset() and .read() bracket a frame in the page.
export function installPassCounter(gl) {
  const counts = { fullscreen: 0, geometry: 0, draws: 0 };
  let inGeometry = false;
  let inFullscreen = false;  // the last draw was full-screen, and nothing has interrupted it since
  let scissored = false;
  const boundary = () => {
    inGeometry = false;
    inFullscreen = false;
  };
  const isFullscreen = (mode, count) =>
    (mode === gl.TRIANGLES && (count === 3 || count === 6)) || (mode === gl.TRIANGLE_STRIP && count === 4) ||
    (mode === gl.TRIANGLE_FAN && count === 4);
  const wrap = (name, before) => {
    const original = gl[name].bind(gl);
    gl[name] = (...args) => {
      before(...args);
      return original(...args);
    };
  };
  wrap('drawArrays', (mode, first, count) => {
    counts.draws += 1;
    if (isFullscreen(mode, count)) {
      if (!(inFullscreen && scissored)) counts.fullscreen += 1;
      boundary();
      inFullscreen = true;
    } else if (!inGeometry) {
      counts.geometry += 1;
      inGeometry = true;
      inFullscreen = false;
    }
  });
  const geometryDraw = () => {
    counts.draws += 1;
    inFullscreen = false;
    if (!inGeometry) {
      counts.geometry += 1;
      inGeometry = true;
    }
  };
  wrap('drawElements', geometryDraw);
  for (const name of ['drawArraysInstanced', 'drawElementsInstanced', 'drawRangeElements'])
    if (typeof gl[name] === 'function') wrap(name, geometryDraw);
  for (const name of ['bindFramebuffer', 'clear', 'colorMask']) wrap(name, boundary);
  wrap('enable', (cap) => { if (cap === gl.SCISSOR_TEST) scissored = true; });
  wrap('disable', (cap) => { if (cap === gl.SCISSOR_TEST) scissored = false; });
  window.benchPasses = {
    reset() {
      counts.fullscreen = counts.geometry = counts.draws = 0;
      inGeometry = inFullscreen = false;
    },
    read() { return { ...counts }; },
  };
}
