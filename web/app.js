// The demo page: a full-window canvas and a controls panel over the JS API of obscura.js. The controls are built
// from the effect table the core exports (effects, their parameters with kinds, ranges and presets, the views); this
// file only decides their layout: one collapsible section per effect, its switch in the heading, the parameters the
// table marks primary up front and the others under "more".
import { createObscura, ObscuraError } from './obscura.js';

const VIEW_LABELS = { final: 'Final', split: 'Split: off | on', ao: 'AO', 'ao-raw': 'Raw AO', 'ao-blur-h': 'AO blur H',
                      normals: 'Normals', depth: 'Depth', mask: 'Mask', 'scene-color': 'HDR colour',
                      'display-color': 'Display colour', 'shading-count': 'Shading count',
                      'base-color': 'Base colour', velocity: 'Motion vectors',
                      'second-layer': 'Second depth layer', 'normals-from-depth': 'Normals from depth' };
// Keys of the page itself (the core's bindings come from obscura.keyBindings).
const PAGE_KEYS = [['h', 'hide / show the controls'], ['o', 'open a scene file']];
const POINTER_HELP = [['left drag', 'orbit'], ['right drag, shift + drag', 'pan'], ['wheel', 'zoom'],
                      ['one finger', 'orbit'], ['two fingers', 'pinch to zoom, move to pan']];
const SLIDER_STEPS = 1000;
// Narrow or touch screens (phones, tablets) start with the panel closed, so that the image is what a visitor sees
// first; style.css makes the panel a sheet along the bottom there.
// 600 CSS pixels: phones in portrait are at most about 430 wide; a 640 x 360 desktop window keeps its panel.
const COMPACT_SCREEN = '(max-width: 600px), (pointer: coarse)';

const $ = (selector) => document.querySelector(selector);
const controls = [];  // {name, update()} per parameter control

function element(tag, properties = {}, ...children) {
  const node = Object.assign(document.createElement(tag), properties);
  node.append(...children);
  return node;
}

function showError(message) {
  $('#error').textContent = message;
  $('#error').hidden = !message;
}

function setStatus(message) { $('#status').textContent = message; }

// --- Parameter controls ------------------------------------------------------------------------------------------

// Slider positions: whole numbers step through their range; real numbers get SLIDER_STEPS positions over
// low .. high (by default the parameter's range), on a logarithmic scale for wide positive ranges (the radius) so
// small values stay reachable.
function sliderScale(parameter, low = parameter.min, high = parameter.max) {
  if (parameter.kind === 'integer') {
    return { min: parameter.min, max: parameter.max, toSlider: (v) => v, fromSlider: (t) => t };
  }
  if (low > 0 && high / low >= 100) {
    const ratio = Math.log(high / low);
    return {
      min: 0,
      max: SLIDER_STEPS,
      toSlider: (v) => Math.round(SLIDER_STEPS * Math.log(v / low) / ratio),
      fromSlider: (t) => Number((low * Math.exp(ratio * t / SLIDER_STEPS)).toPrecision(3)),
    };
  }
  const span = high - low;
  return {
    min: 0,
    max: SLIDER_STEPS,
    toSlider: (v) => Math.round(SLIDER_STEPS * (v - low) / span),
    // Where the number box rounds to the parameter's step, the slider gives that value: what is shown is applied.
    fromSlider: (t) => Number(roundToStep(parameter, Number((low + span * t / SLIDER_STEPS).toPrecision(4)))),
  };
}

// The AO radius is in the scene's units, and its range (1e-4 .. 1e6) is far too wide for one slider: its slider
// spans the scene's default radius (obscura.defaultRadius: 5 % of the scene's bounding-sphere diameter) / 100 ..
// x 100, logarithmic, so the default sits in the middle. The span is re-centred when a scene with another default
// is loaded, and widened to take in a value typed or linked outside it (within the parameter's range).
const FOLLOWS_SCENE = 'ao.radius';
const SCENE_SPAN = 100;

function sceneSpan(parameter, previous, centre, value) {
  const span = previous && previous.centre === centre
    ? { ...previous } : { centre, low: centre / SCENE_SPAN, high: centre * SCENE_SPAN };
  if (Number.isFinite(value) && value > 0) {
    span.low = Math.min(span.low, value);
    span.high = Math.max(span.high, value);
  }
  span.low = Math.max(span.low, parameter.min);
  span.high = Math.min(span.high, parameter.max);
  return span;
}

// A number as its field shows it: rounded to the parameter's step (parameter.step, from the core: a power of ten near
// a thousandth of the range, 1 for integers), so the sun's elevation reads 54.5, not 54.52596. Values under 100 steps
// (fog's density 0.02 on a range of 0 .. 100, the AO's fitted bias 0.0663) and parameters whose step is 0 (ranges
// over decades, which the slider covers logarithmically) show three significant figures instead.
function roundToStep(parameter, value) {
  const v = Number(value);
  if (value === '' || !Number.isFinite(v)) return String(value);
  if (!(parameter.step > 0) || Math.abs(v) < 100 * parameter.step) return String(Number(v.toPrecision(3)));
  const decimals = Math.max(0, -Math.floor(Math.log10(parameter.step) + 1e-9));
  return String(Number((Math.round(v / parameter.step) * parameter.step).toFixed(decimals)));
}

// A parameter's element id: "param-ao-radius" for "ao.radius" (ids with dots are awkward in CSS selectors).
const controlId = (name) => `param-${name.replace(/\./g, '-')}`;
// Its label: the name without its effect's prefix.
const shortName = (parameter) => (parameter.name.startsWith(`${parameter.effect}.`)
  ? parameter.name.slice(parameter.effect.length + 1) : parameter.name).replace(/-/g, ' ');

// A linear RGB triple as the sRGB "#rrggbb" a colour picker shows (IEC 61966-2-1, each channel clamped to 0 .. 1).
function linearToSrgbHex(rgb) {
  const encode = (v) => {
    const c = Math.min(Math.max(Number.isFinite(v) ? v : 0, 0), 1);
    const s = c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055;
    return Math.round(s * 255).toString(16).padStart(2, '0');
  };
  return `#${rgb.map(encode).join('')}`;
}

function parameterControl(obscura, parameter) {
  const id = controlId(parameter.name);
  const label = element('label', { htmlFor: id, textContent: shortName(parameter),
                                   title: `${parameter.name}: ${parameter.help} (${parameter.range})` });
  const row = element('div', { className: `parameter ${parameter.kind}` }, label);
  const apply = (value) => {
    try {
      obscura.set(parameter.name, value);
      showError('');
    } catch (e) {
      showError(e.message);
      refreshControls(obscura);  // back to the value the core kept
    }
  };

  if (parameter.kind === 'switch') {
    const box = element('input', { type: 'checkbox', id });
    box.addEventListener('change', () => apply(box.checked ? 'on' : 'off'));
    row.append(box);
    return { row, update: () => { box.checked = obscura.get(parameter.name) === 'on'; } };
  }
  if (parameter.kind === 'choice') {
    const select = element('select', { id });
    for (const choice of parameter.choices) select.append(element('option', { value: choice, textContent: choice }));
    // A preset the current values no longer match reads as "custom".
    const custom = element('option', { value: '', textContent: 'custom', disabled: true });
    select.append(custom);
    select.addEventListener('change', () => apply(select.value));
    row.append(select);
    return { row, update: () => { select.value = obscura.get(parameter.name); } };
  }
  if (parameter.kind === 'text') {
    // Named built-ins (lighting.environment: sky, uniform; grading.lut: none) in a list, which also shows a file in
    // use; a dropped .hdr or .cube file sets it too (loadFiles).
    const select = element('select', { id });
    for (const choice of parameter.choices || []) {
      select.append(element('option', { value: choice, textContent: choice }));
    }
    const other = element('option', { value: '', textContent: '', disabled: true });
    select.append(other);
    select.addEventListener('change', () => apply(select.value));
    row.append(select, element('span', { className: 'hint', textContent: ' or drop a file', title: parameter.range }));
    return {
      row,
      update: () => {
        const value = obscura.get(parameter.name);
        const builtIn = (parameter.choices || []).includes(value);
        other.value = builtIn ? '' : value;
        other.textContent = builtIn ? '' : value.split('/').pop();
        select.value = value;
      },
    };
  }
  if (parameter.kind === 'color') {
    // A linear colour: the picker shows (and sets, as "#rrggbb") its sRGB encoding clamped to 0 .. 1; the text field
    // takes linear "r,g,b" beyond 1 too (HDR).
    const picker = element('input', { type: 'color', id, title: 'sRGB' });
    const text = element('input', { type: 'text', size: 14, title: parameter.range,
                                    ariaLabel: `${parameter.name} value` });
    picker.addEventListener('input', () => apply(picker.value));
    text.addEventListener('change', () => apply(text.value));
    row.append(picker, text);
    return {
      row,
      update: () => {
        const value = obscura.get(parameter.name);
        picker.value = linearToSrgbHex(value.split(',').map(Number));
        if (document.activeElement !== text) text.value = value;
      },
    };
  }
  let scale = sliderScale(parameter);
  const slider = element('input', { type: 'range', id, min: scale.min, max: scale.max, step: 1,
                                    title: parameter.range });
  // For the radius: the span its slider covers now (sceneSpan), also in the slider's data-low and data-high.
  let span = null;
  const followScene = (value) => {
    const next = sceneSpan(parameter, span, obscura.defaultRadius, value);
    if (span && next.low === span.low && next.high === span.high && next.centre === span.centre) return;
    span = next;
    scale = sliderScale(parameter, span.low, span.high);
    slider.dataset.low = String(span.low);
    slider.dataset.high = String(span.high);
    slider.title = `${Number(span.low.toPrecision(3))} .. ${Number(span.high.toPrecision(3))} on this slider ` +
                   `(the scene's default ${span.centre} in the middle); ${parameter.range} typed`;
  };
  const number = element('input', { type: 'number', min: parameter.min, max: parameter.max,
                                    step: parameter.kind === 'integer' ? 1 : parameter.step || 'any',
                                    title: parameter.range, ariaLabel: `${parameter.name} value` });
  // A slow parameter (parameter.slow: the sky is made again) is applied when the drag ends; the number follows it.
  if (parameter.slow) {
    slider.addEventListener('input', () => {
      number.value = roundToStep(parameter, scale.fromSlider(Number(slider.value)));
    });
    slider.addEventListener('change', () => apply(scale.fromSlider(Number(slider.value))));
  } else {
    slider.addEventListener('input', () => apply(scale.fromSlider(Number(slider.value))));
  }
  number.addEventListener('change', () => apply(number.value));
  row.append(slider, number);
  // Bias, intensity and contrast default to 'auto' (fitted to the ray-traced reference for the preset and radius):
  // the controls then show the fitted value, and the checkbox returns to it.
  const auto = (parameter.choices || []).includes('auto')
    ? element('input', { type: 'checkbox', id: `${id}-auto`, title: 'fitted to the ray-traced reference' })
    : null;
  if (auto) {
    // dof.focus's 'auto' is resolved on the GPU and has no value here: unchecked, it takes the slider's.
    const manual = () => {
      const value = obscura.effective(parameter.name);
      return Number.isFinite(Number(value)) ? value : String(scale.fromSlider(Number(slider.value)));
    };
    auto.addEventListener('change', () => apply(auto.checked ? 'auto' : manual()));
    row.append(element('label', { htmlFor: `${id}-auto`, className: 'auto', textContent: 'auto' }, auto));
  }
  return {
    row,
    update: () => {
      const value = obscura.effective(parameter.name);
      if (parameter.name === FOLLOWS_SCENE) followScene(Number(value));
      slider.value = scale.toSlider(Number(value));
      if (document.activeElement !== number) number.value = roundToStep(parameter, value);
      if (auto) auto.checked = obscura.get(parameter.name) === 'auto';
    },
  };
}

function buildControls(obscura) {
  // The frame's own parameters (the quality preset) first, then a section per effect, in frame order.
  for (const parameter of obscura.parameters.filter((p) => !p.effect)) {
    const control = parameterControl(obscura, parameter);
    $('#frame-parameters').append(control.row);
    controls.push(control);
  }
  for (const effect of obscura.effects) {
    const parameters = obscura.parameters.filter((p) => p.effect === effect.name);
    if (!parameters.length) continue;
    const section = element('details', { className: 'effect', id: `effect-${effect.name}`, open: true });
    const summary = element('summary', { textContent: effect.title });
    const main = element('div', { className: 'parameters' });
    const more = element('details', { className: 'more' }, element('summary', { textContent: 'more' }));
    section.append(summary, main);
    for (const parameter of parameters) {
      const control = parameterControl(obscura, parameter);
      controls.push(control);
      if (parameter.name === effect.name) {
        // The effect's switch sits in its heading; clicking the box must not fold the section.
        const box = control.row.querySelector('input');
        box.addEventListener('click', (e) => e.stopPropagation());
        box.title = `${effect.title} on / off`;
        summary.append(box);
      } else {
        (parameter.primary ? main : more).append(control.row);
      }
    }
    if (more.children.length > 1) section.append(more);
    $('#effects').append(section);
  }

  for (const view of obscura.views) {
    const radio = element('input', { type: 'radio', name: 'view', value: view, id: `view-${view}` });
    radio.addEventListener('change', () => obscura.setView(view));
    $('#views').append(element('label', {}, radio, ` ${VIEW_LABELS[view] ?? view}`));
  }

  // What the split view compares: each effect's switch by the effect's title, switches within an effect by name.
  for (const name of obscura.compareSwitches) {
    $('#compare').append(element('option', { value: name, textContent: compareLabel(obscura, name) }));
  }
  $('#compare').addEventListener('change', () => {
    try {
      obscura.setCompare($('#compare').value);
      obscura.setView('split');
      showError('');
    } catch (e) {
      showError(e.message);
    }
  });

  const rows = [...obscura.keyBindings.map((b) => [b.label, b.description]), ...PAGE_KEYS, ...POINTER_HELP];
  for (const [key, description] of rows) {
    $('#shortcuts').append(element('tr', {}, element('td', { textContent: key }),
                                   element('td', { textContent: description })));
  }
}

function refreshControls(obscura) {
  for (const control of controls) control.update();
  refreshTimeline(obscura);
  refreshCamera(obscura);
  const view = obscura.view;
  const radio = document.getElementById(`view-${view}`);
  if (radio) radio.checked = true;
  $('#split-divider').hidden = view !== 'split';
  const compare = obscura.compare;
  $('#compare').value = compare;
  $('#split-off').textContent = `${compareLabel(obscura, compare)} off`;
  $('#split-on').textContent = `${compareLabel(obscura, compare)} on`;
}

function compareLabel(obscura, name) {
  const effect = obscura.effects.find((e) => e.name === name);
  return effect ? effect.title : name;
}

// A control's action: run it and clear the error line, or show what the core refused and `refresh` the controls from
// the state the core kept.
function guarded(refresh) {
  return (action) => {
    try {
      action();
      showError('');
    } catch (e) {
      showError(e.message);
      refresh();
    }
  };
}

// --- Camera ------------------------------------------------------------------------------------------------------

// The Camera menu: the free orbit camera, then the scene's own cameras (glTF cameras on nodes) by name; the
// orthographic box switches the free camera's projection, from the view shown.
function wireCamera(obscura) {
  const act = guarded(() => refreshCamera(obscura));
  $('#camera').addEventListener('change', (e) => act(() => obscura.setCamera(e.target.value)));
  $('#orthographic').addEventListener('change', (e) => act(() => obscura.setOrthographic(e.target.checked)));
}

function refreshCamera(obscura) {
  const camera = obscura.camera();
  const select = $('#camera');
  // By index: names may be shared or empty; the core's choice names the same camera by its name where it can.
  const choices = [['free', 'Free (orbit)'],
                   ...camera.cameras.map((c, i) => [String(i), `${c.name}${c.orthographic ? ' (orthographic)' : ''}`])];
  const signature = JSON.stringify(choices);
  if (select.dataset.choices !== signature) {
    select.replaceChildren(...choices.map(([value, label]) => element('option', { value, textContent: label })));
    select.dataset.choices = signature;
  }
  const index = camera.cameras.findIndex((c, i) => c.name === camera.choice || String(i) === camera.choice);
  select.value = camera.choice === 'free' || index < 0 ? 'free' : String(index);
  select.disabled = camera.cameras.length === 0;
  $('#orthographic').checked = camera.orthographic;
}

// --- Timeline ----------------------------------------------------------------------------------------------------

// The animation's controls, shown where the scene has animations. The slider moves in frames of the frame step
// (obscura's frameInterval, 1/60 s), so a time chosen with it is a whole frame; the speeds offered are these and
// whatever speed a link gave.
const SPEEDS = [0.1, 0.25, 0.5, 1, 2, 4];

function wireTimeline(obscura) {
  const act = guarded(() => refreshTimeline(obscura));
  $('#play').addEventListener('click', () => act(() => (obscura.playing ? obscura.pause() : obscura.play())));
  $('#frame-back').addEventListener('click', () => act(() => obscura.stepFrames(-1)));
  $('#frame-on').addEventListener('click', () => act(() => obscura.stepFrames(1)));
  $('#animation').addEventListener('change', (e) => act(() => obscura.setAnimation(e.target.value)));
  $('#time').addEventListener('input', (e) => {
    act(() => obscura.setTime(Number(e.target.value) * obscura.timeline().frameInterval));
  });
  $('#speed').addEventListener('change', (e) => act(() => obscura.setSpeed(Number(e.target.value))));
  $('#loop').addEventListener('change', (e) => act(() => obscura.setLoop(e.target.checked)));
  obscura.addEventListener('timeupdate', () => refreshTimeline(obscura));
}

function refreshTimeline(obscura) {
  const t = obscura.timeline();
  $('#timeline').hidden = t.animations.length === 0;
  if (!t.animations.length) return;
  // The choices: every animation by index (a name may be shared or empty), then all together, then the rest pose.
  const select = $('#animation');
  const choices = [...t.animations.map((name, i) => [String(i), name || `animation ${i}`]),
                   ['all', 'all together'], ['none', 'none (rest pose)']];
  const signature = JSON.stringify(choices);
  if (select.dataset.choices !== signature) {
    select.replaceChildren(...choices.map(([value, label]) => element('option', { value, textContent: label })));
    select.dataset.choices = signature;
  }
  const index = t.animations.indexOf(t.animation);
  select.value = ['all', 'none'].includes(t.animation) ? t.animation : String(index >= 0 ? index : t.animation);

  $('#play').textContent = t.playing ? 'Pause' : 'Play';
  $('#play').disabled = $('#frame-back').disabled = $('#frame-on').disabled = t.duration <= 0;
  const slider = $('#time');
  slider.max = String(Math.max(1, Math.round(t.duration / t.frameInterval)));
  if (!slider.matches(':active')) slider.value = String(Math.round(t.time / t.frameInterval));  // not under a drag
  slider.disabled = t.duration <= 0;
  $('#time-text').textContent = `${t.time.toFixed(2)} / ${t.duration.toFixed(2)} s`;

  const speed = $('#speed');
  const speeds = SPEEDS.includes(t.speed) ? SPEEDS : [...SPEEDS, t.speed].sort((a, b) => a - b);
  if (speed.dataset.speeds !== String(speeds)) {
    speed.replaceChildren(...speeds.map((v) => element('option', { value: String(v), textContent: `x ${v}` })));
    speed.dataset.speeds = String(speeds);
  }
  speed.value = String(t.speed);
  $('#loop').checked = t.loop;
}

// --- Stats -------------------------------------------------------------------------------------------------------

// Every figure is a measurement: the last drawn frame's time in the renderer, the GPU time of its passes once the
// timer queries come back (a few animation frames later, also while idle), and the frame time only where frames
// were drawn back to back.
function showStats(obscura) {
  const s = obscura.stats();
  const frame = s.frameMs > 0 ? `${s.frameMs.toFixed(1)} ms (${(1000 / s.frameMs).toFixed(0)} fps)`
                              : '- (drawn on change only: redraw continuously to measure)';
  const r = s.render;
  const ratio = r.pixelRatio < r.devicePixelRatio ? `pixel ratio ${r.pixelRatio} (device ${r.devicePixelRatio})`
                                                  : `pixel ratio ${r.pixelRatio}`;
  const dynamic = !r.dynamic ? 'fixed'
    : `dynamic: ${r.meanMs > 0 ? `${r.meanMs.toFixed(1)} ms` : 'measuring'} (${r.measuredBy}), target ${r.targetMs} ms`;
  const cheap = s.cheapFrame ? ' (the last a cheap quick-start frame: the full one follows)' : '';
  const lines = [`${s.width} x ${s.height} px, ${ratio}, ${s.frames} frames drawn${cheap}`,
                 `render ${r.width} x ${r.height}: scale ${r.scale.toFixed(2)}, ${dynamic}`,
                 `frame  ${frame}`,
                 `host   ${s.frames > 0 ? s.lastHostMs.toFixed(2) : '-'} ms in the renderer, last frame`];
  lines.push(startupLine(obscura));
  if (s.passMs) {
    lines.push('GPU per pass, a recent frame (EXT_disjoint_timer_query):');
    let total = 0;
    for (const pass of obscura.passes) {
      const ms = s.passMs[pass];
      if (ms !== null) total += ms;
      const doneBy = s.passesDoneBy[pass];
      const by = doneBy ? ` (done by ${doneBy})` : '';
      lines.push(`  ${pass.padEnd(10)} ${ms === null ? '   -' : ms.toFixed(2)} ms${by}`);
    }
    lines.push(`  ${'total'.padEnd(10)} ${total.toFixed(2)} ms`);
  } else {
    lines.push(s.timerQueries ? 'GPU per pass: waiting for the first results'
                              : 'GPU per pass: needs EXT_disjoint_timer_query (not offered here)');
  }
  if (s.history) lines.push(`history ${s.history.frames} frames (dropped ${s.history.drops} times)`);
  if (s.contextLost) lines.push('WebGL context lost: waiting for the browser to restore it');
  if (s.error) lines.push(`stopped: ${s.error}`);
  $('#stats').textContent = lines.join('\n');
}

// --- Scenes ------------------------------------------------------------------------------------------------------

function showScene(scene) {
  // The radius a scene gets by default: 5 % of its bounding sphere's diameter (the built-in scene: 1 m).
  $('#scene-name').textContent = `${scene.name}: ${scene.triangles.toLocaleString('en')} triangles, ` +
                                 `AO radius ${scene.defaultRadius} by default`;
  setStatus(scene.warnings.length ? `${scene.warnings.length} warning(s): ${scene.warnings.join('; ')}` : '');
}

async function loadFiles(obscura, files) {
  const progress = $('#load-progress');
  progress.value = 0;
  progress.hidden = false;
  document.body.dataset.loading = 'true';
  showError('');
  setStatus(`Loading ${Array.from(files).map((f) => f.name).join(', ')}…`);
  try {
    showScene(await obscura.loadFiles(files, { onProgress: (fraction) => { progress.value = fraction; } }));
    refreshControls(obscura);  // an .hdr sets lighting.environment, a .cube grading.lut
  } catch (e) {
    // The core keeps the previous scene on screen; say why this one was refused.
    setStatus('');
    showError(e instanceof ObscuraError ? e.message : `cannot load: ${e.message}`);
  } finally {
    progress.hidden = true;
    delete document.body.dataset.loading;
  }
}

function wireScenes(obscura) {
  $('#file-input').addEventListener('change', (e) => {
    if (e.target.files.length) loadFiles(obscura, e.target.files);
    e.target.value = '';  // choosing the same file again loads it again
  });
  $('#builtin-scene').addEventListener('click', () => {
    showScene(obscura.loadBuiltinScene());
    showError('');
  });

  // Drag and drop anywhere on the page; the counter tracks enter/leave pairs of nested elements.
  let dragDepth = 0;
  const carriesFiles = (e) => Array.from(e.dataTransfer?.types ?? []).includes('Files');
  window.addEventListener('dragenter', (e) => {
    if (!carriesFiles(e)) return;
    dragDepth += 1;
    $('#drop-overlay').hidden = false;
    e.preventDefault();
  });
  window.addEventListener('dragover', (e) => { if (carriesFiles(e)) e.preventDefault(); });
  window.addEventListener('dragleave', () => {
    dragDepth = Math.max(0, dragDepth - 1);
    if (dragDepth === 0) $('#drop-overlay').hidden = true;
  });
  window.addEventListener('drop', (e) => {
    e.preventDefault();
    dragDepth = 0;
    $('#drop-overlay').hidden = true;
    if (e.dataTransfer?.files.length) loadFiles(obscura, e.dataTransfer.files);
  });
}

// --- Keyboard, panel, URL ----------------------------------------------------------------------------------------

function wireKeys(obscura) {
  window.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const target = e.target;
    if (target instanceof HTMLSelectElement ||
        (target instanceof HTMLInputElement && !['range', 'checkbox', 'radio'].includes(target.type))) return;
    // A focused slider or radio button keeps its arrow and Home keys (they move it); elsewhere they step the
    // animation and go back to its start.
    if (target instanceof HTMLInputElement && ['range', 'radio'].includes(target.type) &&
        (e.key.startsWith('Arrow') || e.key === 'Home')) return;
    if (e.key === 'h') {
      togglePanel();
    } else if (e.key === 'o') {
      $('#file-input').click();
    } else {
      try {
        if (!obscura.handleKey(e.key)) return;
        showError('');
      } catch (error) {
        showError(error.message);
      }
    }
    e.preventDefault();
  });
}

function togglePanel() { setPanelOpen($('#panel').classList.contains('collapsed')); }

function setPanelOpen(open) {
  $('#panel').classList.toggle('collapsed', !open);
  $('#panel').classList.toggle('expanded', open);
  $('#panel-toggle').textContent = open ? 'Hide' : 'Controls';
  $('#panel-toggle').setAttribute('aria-expanded', String(open));
}

// The URL follows every change (replaceState, so the back button is not flooded), at most a few times a second.
function wireUrl(obscura) {
  let pending = null;
  obscura.addEventListener('change', () => {
    if (pending) return;
    pending = setTimeout(() => {
      pending = null;
      history.replaceState(null, '', `${location.pathname}?${obscura.state()}${urlFlags()}`);
    }, 150);
  });
}

// Page flags in the URL that are not part of the shared state: `debug-gl` checks glGetError after every pass.
const PAGE_FLAGS = ['debug-gl'];

// The URL's query without the page flags: what setState() takes.
function stateFromUrl() {
  const params = new URLSearchParams(location.search);
  for (const flag of PAGE_FLAGS) params.delete(flag);
  return params.toString();
}

// The page flags present in the URL, to keep when the state is written back.
function urlFlags() {
  const params = new URLSearchParams(location.search);
  return PAGE_FLAGS.filter((flag) => params.has(flag)).map((flag) => `&${flag}`).join('');
}

// Start-up, from the JS API's figures (obscura.startup()) and the page's own: how long after navigation the first frame
// was on screen (performance.now() counts from the navigation's start).
let shownAt = null;
function startupLine(obscura) {
  const s = obscura.startup();
  const ms = (v) => (v === null || v === undefined ? '-' : `${Math.round(v)}`);
  const parts = Object.entries(s.coreParts).filter(([, v]) => v >= 1).sort((a, b) => b[1] - a[1])
    .map(([name, v]) => `${name} ${ms(v)}`).join(', ');
  // Quick start: the first frame was a cheap one; the full frame followed after it and the warming frames.
  const q = s.quickStart;
  const quick = q && q.cheapFrames > 0
    ? ` (cheap: the lit scene; the full frame ${ms(s.fullFrameMs)} ms, after ${q.cheapFrames} cheap frames that ` +
      `warmed ${q.warmed.length} passes)`
    : '';
  return `start  wasm ${ms(s.wasmMs)} ms, core ${ms(s.coreMs)} ms${parts ? ` (${parts})` : ''}, ` +
         `first frame ${ms(s.firstFrameMs)} ms${quick}; shown ` +
         `${shownAt === null ? '-' : (shownAt / 1000).toFixed(2)} s after navigation`;
}

async function main() {
  let obscura;
  if (matchMedia(COMPACT_SCREEN).matches) setPanelOpen(false);
  try {
    // The page's frames follow the frame time (resolution.dynamic on), and its first frame is a cheap one
    // (resolution.quick-start on): the API's defaults are off.
    obscura = await createObscura($('#view'), { checkGlErrors: new URLSearchParams(location.search).has('debug-gl'),
                                                dynamicResolution: true, quickStart: true });
  } catch (e) {
    showError(`Obscura cannot start here: ${e.message}`);
    $('#stats').textContent = '';
    return;
  }
  window.obscura = obscura;  // for the console and for tests

  buildControls(obscura);
  $('#panel-toggle').addEventListener('click', togglePanel);
  const linkedState = stateFromUrl();
  if (linkedState) {
    try {
      obscura.setState(linkedState);
    } catch (e) {
      showError(`This link's view was not applied: ${e.message}`);
    }
  }
  showScene(obscura.scene());
  // Controls follow every change, whoever made it: the panel, a key, the pointer, a script through the API.
  refreshControls(obscura);
  obscura.addEventListener('change', () => refreshControls(obscura));
  wireScenes(obscura);
  wireTimeline(obscura);
  wireCamera(obscura);
  wireKeys(obscura);
  wireUrl(obscura);
  $('#continuous').addEventListener('change', (e) => obscura.setContinuous(e.target.checked));
  setInterval(() => showStats(obscura), 250);
  document.body.dataset.ready = 'true';
  await obscura.firstFrame;
  shownAt = performance.now();
  document.body.dataset.shownScale = String(obscura.stats().render.scale);
  document.body.dataset.shown = String(shownAt);
}

main();
