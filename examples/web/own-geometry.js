// A page's own minimal WebGL 1 drawing (its meshes, its shaders, its camera) with Obscura's AO on it
// (createAmbientOcclusion; docs/api.md, "In the browser"). Draws one frame per call of draw().
import { createAmbientOcclusion } from 'obscura-webgl';

const vertexShader = `
attribute vec3 a_position;
attribute vec3 a_normal;
uniform mat4 u_view;
uniform mat4 u_projection;
varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
varying vec3 v_worldNormal;
void main() {
  vec4 viewPosition = u_view * vec4(a_position, 1.0);
  v_viewPosition = viewPosition.xyz;
  v_viewNormal = mat3(u_view) * a_normal;
  v_worldNormal = a_normal;
  gl_Position = u_projection * viewPosition;
}`;
const gbufferMain = `
uniform float u_near;
uniform float u_far;
varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
void main() { gl_FragColor = obscuraGBuffer(normalize(v_viewNormal), -v_viewPosition.z, u_near, u_far); }`;
const colorShader = `
precision mediump float;
uniform vec3 u_color;
varying vec3 v_worldNormal;
void main() {
  float sun = max(dot(normalize(v_worldNormal), normalize(vec3(0.4, 0.8, 0.45))), 0.0);
  gl_FragColor = vec4(u_color * (0.35 + 0.65 * sun), 1.0);
}`;

function link(gl, vertex, fragment) {
  const program = gl.createProgram();
  for (const [type, source] of [[gl.VERTEX_SHADER, vertex], [gl.FRAGMENT_SHADER, fragment]]) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
    gl.attachShader(program, shader);
  }
  gl.bindAttribLocation(program, 0, 'a_position');
  gl.bindAttribLocation(program, 1, 'a_normal');
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
  return program;
}

// A flat-shaded box as interleaved position + normal triangles.
function box(gl, lo, hi, color) {
  const [x0, y0, z0] = lo, [x1, y1, z1] = hi;
  const faces = [
    [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1], [0, 0, 1]],
    [[x1, y0, z0], [x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [0, 0, -1]],
    [[x1, y0, z1], [x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [1, 0, 0]],
    [[x0, y0, z0], [x0, y0, z1], [x0, y1, z1], [x0, y1, z0], [-1, 0, 0]],
    [[x0, y1, z1], [x1, y1, z1], [x1, y1, z0], [x0, y1, z0], [0, 1, 0]],
    [[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1], [0, -1, 0]],
  ];
  const data = [];
  for (const [a, b, c, d, n] of faces) for (const p of [a, b, c, a, c, d]) data.push(...p, ...n);
  const buffer = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
  gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(data), gl.STATIC_DRAW);
  gl.bindBuffer(gl.ARRAY_BUFFER, null);
  return { buffer, count: data.length / 6, color };
}

function perspective(fovy, aspect, near, far) {
  const f = 1 / Math.tan((fovy * Math.PI) / 360);
  const depth = 1 / (near - far);
  return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * depth, -1, 0, 0, 2 * far * near * depth, 0];
}
function lookAt(eye, target, up) {
  const sub = (a, b) => a.map((v, i) => v - b[i]);
  const norm = (v) => v.map((x) => x / Math.hypot(...v));
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const f = norm(sub(target, eye)), s = norm(cross(f, up)), u = cross(s, f);
  return [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, -dot(s, eye), -dot(u, eye), dot(f, eye), 1];
}

export async function startOwnGeometry(canvas, { checkGlErrors = false } = {}) {
  // The page's context first; Obscura joins it.
  const gl = canvas.getContext('webgl', { antialias: false, depth: true });
  const ao = await createAmbientOcclusion(canvas, { checkGlErrors });
  ao.set('ao.radius', 0.6);
  const gbufferProgram = link(gl, vertexShader, `precision highp float;\n${ao.gbufferGlsl}\n${gbufferMain}`);
  const colorProgram = link(gl, vertexShader, colorShader);
  const meshes = [box(gl, [-6, -0.1, -6], [6, 0, 6], [0.8, 0.8, 0.78]),
                  box(gl, [-1.5, 0, -1], [-0.5, 1, 0], [0.8, 0.3, 0.25]),
                  box(gl, [0.2, 0, -1.5], [1.4, 1.8, -0.3], [0.3, 0.45, 0.8]),
                  box(gl, [0.6, 0, 0.8], [1.2, 0.6, 1.4], [0.8, 0.8, 0.78])];
  const camera = { eye: [2.5, 2.6, 4.5], target: [0, 0.4, -0.3], up: [0, 1, 0], fovy: 50, near: 0.1, far: 30 };

  function drawMeshes(program, view, projection) {
    gl.useProgram(program);
    gl.uniformMatrix4fv(gl.getUniformLocation(program, 'u_view'), false, view);
    gl.uniformMatrix4fv(gl.getUniformLocation(program, 'u_projection'), false, projection);
    gl.uniform1f(gl.getUniformLocation(program, 'u_near'), camera.near);
    gl.uniform1f(gl.getUniformLocation(program, 'u_far'), camera.far);
    gl.enableVertexAttribArray(0);
    gl.enableVertexAttribArray(1);
    for (const mesh of meshes) {
      gl.uniform3fv(gl.getUniformLocation(program, 'u_color'), mesh.color);
      gl.bindBuffer(gl.ARRAY_BUFFER, mesh.buffer);
      gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 24, 0);
      gl.vertexAttribPointer(1, 3, gl.FLOAT, false, 24, 12);
      gl.drawArrays(gl.TRIANGLES, 0, mesh.count);
    }
    // Back to the default state Obscura expects between its calls.
    gl.disableVertexAttribArray(0);
    gl.disableVertexAttribArray(1);
    gl.bindBuffer(gl.ARRAY_BUFFER, null);
    gl.useProgram(null);
  }

  let withAo = true;
  function draw() {
    // The drawing buffer follows the canvas's CSS size.
    const ratio = window.devicePixelRatio || 1;
    const width = Math.max(1, Math.round(canvas.clientWidth * ratio));
    const height = Math.max(1, Math.round(canvas.clientHeight * ratio));
    if (canvas.width !== width || canvas.height !== height) Object.assign(canvas, { width, height });
    const view = lookAt(camera.eye, camera.target, camera.up);
    const projection = perspective(camera.fovy, width / height, camera.near, camera.far);

    ao.beginGBuffer(width, height);
    gl.enable(gl.DEPTH_TEST);
    drawMeshes(gbufferProgram, view, projection);
    gl.disable(gl.DEPTH_TEST);
    const texture = ao.ambientOcclusion(camera);

    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.viewport(0, 0, width, height);
    gl.clearColor(0.62, 0.74, 0.9, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    drawMeshes(colorProgram, view, projection);
    gl.disable(gl.DEPTH_TEST);
    if (withAo) ao.composite(width, height);
    return texture;
  }
  draw();
  return {
    ao, gl, camera, draw,
    setAo(on) { withAo = on; draw(); },
    // The pixel (rows from the top) a world point lands on.
    project(point) {
      const m = [perspective(camera.fovy, canvas.width / canvas.height, camera.near, camera.far),
                 lookAt(camera.eye, camera.target, camera.up)];
      const apply = (a, v) => [0, 1, 2, 3].map((r) => a[r] * v[0] + a[4 + r] * v[1] + a[8 + r] * v[2] +
                                                      a[12 + r] * v[3]);
      const clip = apply(m[0], apply(m[1], [...point, 1]));
      return [Math.floor((clip[0] / clip[3] * 0.5 + 0.5) * canvas.width),
              canvas.height - 1 - Math.floor((clip[1] / clip[3] * 0.5 + 0.5) * canvas.height)];
    },
  };
}
