// AO on the caller's own geometry: a minimal GLES 2 "engine" of its own (its meshes in its buffers, its shaders, its
// framebuffer, its lighting) that asks Obscura only for the ambient obscurance.
//
// Each frame:
//   1. renderer.beginGBuffer(w, h), then the engine draws its meshes with its G-buffer shader, whose fragment stage
//      is Obscura's chunk obscura_gbuffer.glsl plus one line: gl_FragColor = obscuraGBuffer(...);
//   2. the engine draws its lit colour into its own framebuffer, as it always did;
//   3. renderer.ambientOcclusion(camera) runs the AO and returns its texture;
//      renderer.compositeAmbientOcclusion(colour) multiplies it in.
//
//   own_geometry OUT.png [--size WxH]   (EGL surfaceless; the engine calls libGLESv2 itself)
// Exits 1 unless the AO darkens where a box stands on the floor and leaves the open floor lit.
#include <GLES2/gl2.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <obscura/headless.h>
#include <obscura/obscura.h>
#include <obscura/offscreen.h>

namespace {

// --- The engine's math: column-major 4x4 matrices, as GL wants them. --------------------------------------------
struct Mat4 {
  float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};
Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) sum += a.m[k * 4 + row] * b.m[c * 4 + k];
      r.m[c * 4 + row] = sum;
    }
  return r;
}
Mat4 perspective(float fovyDegrees, float aspect, float near, float far) {
  const float f = 1.0f / std::tan(fovyDegrees * 3.14159265f / 360.0f);
  Mat4 p;
  p.m[0] = f / aspect;
  p.m[5] = f;
  p.m[10] = (far + near) / (near - far);
  p.m[11] = -1.0f;
  p.m[14] = 2.0f * far * near / (near - far);
  p.m[15] = 0.0f;
  return p;
}
void normalize(float v[3]) {
  const float l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3; ++i) v[i] /= l;
}
Mat4 lookAt(const float eye[3], const float target[3], const float up[3]) {
  float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
  normalize(f);
  float s[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]};
  normalize(s);
  const float u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
  Mat4 v;
  for (int i = 0; i < 3; ++i) {
    v.m[i * 4 + 0] = s[i];
    v.m[i * 4 + 1] = u[i];
    v.m[i * 4 + 2] = -f[i];
  }
  v.m[12] = -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
  v.m[13] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
  v.m[14] = f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2];
  return v;
}

// --- The engine's meshes: flat-shaded boxes (the floor is a flat one). ------------------------------------------
struct Mesh {
  GLuint buffer = 0;  // interleaved position, normal
  GLsizei vertices = 0;
  float color[3];
};
Mesh makeBox(const float lo[3], const float hi[3], const float color[3]) {
  std::vector<float> v;
  auto quad = [&](const float a[3], const float b[3], const float c[3], const float d[3], const float n[3]) {
    for (const float* p : {a, b, c, a, c, d}) v.insert(v.end(), {p[0], p[1], p[2], n[0], n[1], n[2]});
  };
  const float x0 = lo[0], y0 = lo[1], z0 = lo[2], x1 = hi[0], y1 = hi[1], z1 = hi[2];
  const float p[8][3] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                         {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}};
  const float nx[3] = {1, 0, 0}, mx[3] = {-1, 0, 0}, ny[3] = {0, 1, 0}, my[3] = {0, -1, 0}, nz[3] = {0, 0, 1},
              mz[3] = {0, 0, -1};
  quad(p[4], p[5], p[6], p[7], nz);  // counter-clockwise seen from outside
  quad(p[1], p[0], p[3], p[2], mz);
  quad(p[5], p[1], p[2], p[6], nx);
  quad(p[0], p[4], p[7], p[3], mx);
  quad(p[7], p[6], p[2], p[3], ny);
  quad(p[0], p[1], p[5], p[4], my);
  Mesh mesh;
  glGenBuffers(1, &mesh.buffer);
  glBindBuffer(GL_ARRAY_BUFFER, mesh.buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  mesh.vertices = static_cast<GLsizei>(v.size() / 6);
  for (int i = 0; i < 3; ++i) mesh.color[i] = color[i];
  return mesh;
}

// --- The engine's shaders. -------------------------------------------------------------------------------------
const char* kVertex = R"(
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
}
)";
// The G-buffer pass: Obscura's chunk, and one line of the engine's.
const char* kGBufferMain = R"(
uniform float u_near;
uniform float u_far;
varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
void main() { gl_FragColor = obscuraGBuffer(normalize(v_viewNormal), -v_viewPosition.z, u_near, u_far); }
)";
// The engine's own lighting: one sun and a flat sky term, no occlusion of its own.
const char* kColorFragment = R"(
precision mediump float;
uniform vec3 u_color;
varying vec3 v_worldNormal;
void main() {
  vec3 n = normalize(v_worldNormal);
  float sun = max(dot(n, normalize(vec3(0.4, 0.8, 0.45))), 0.0);
  gl_FragColor = vec4(u_color * (0.35 + 0.65 * sun), 1.0);
}
)";

GLuint compile(GLenum stage, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("shader: ") + log);
  }
  return shader;
}
GLuint link(const std::string& vertex, const std::string& fragment) {
  const GLuint program = glCreateProgram();
  glAttachShader(program, compile(GL_VERTEX_SHADER, vertex));
  glAttachShader(program, compile(GL_FRAGMENT_SHADER, fragment));
  glBindAttribLocation(program, 0, "a_position");
  glBindAttribLocation(program, 1, "a_normal");
  glLinkProgram(program);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("program does not link");
  return program;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void drawMeshes(GLuint program, const std::vector<Mesh>& meshes, const Mat4& view, const Mat4& projection) {
  glUseProgram(program);
  glUniformMatrix4fv(glGetUniformLocation(program, "u_view"), 1, GL_FALSE, view.m);
  glUniformMatrix4fv(glGetUniformLocation(program, "u_projection"), 1, GL_FALSE, projection.m);
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);
  for (const Mesh& mesh : meshes) {
    glUniform3fv(glGetUniformLocation(program, "u_color"), 1, mesh.color);
    glBindBuffer(GL_ARRAY_BUFFER, mesh.buffer);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    glDrawArrays(GL_TRIANGLES, 0, mesh.vertices);
  }
  // Back to the state Obscura expects of its callers (obscura.h): nothing bound, depth test off.
  glDisableVertexAttribArray(0);
  glDisableVertexAttribArray(1);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glUseProgram(0);
}

// The pixel (top-down rows) a world point lands on.
void project(const Mat4& viewProjection, const float p[3], int width, int height, int* x, int* y) {
  float clip[4];
  for (int row = 0; row < 4; ++row)
    clip[row] = viewProjection.m[0 * 4 + row] * p[0] + viewProjection.m[1 * 4 + row] * p[1] +
                viewProjection.m[2 * 4 + row] * p[2] + viewProjection.m[3 * 4 + row];
  *x = static_cast<int>((clip[0] / clip[3] * 0.5f + 0.5f) * static_cast<float>(width));
  *y = height - 1 - static_cast<int>((clip[1] / clip[3] * 0.5f + 0.5f) * static_cast<float>(height));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUT.png [--size WxH]\n", argv[0]);
    return 2;
  }
  int width = 640, height = 400;
  if (argc >= 4 && std::string(argv[2]) == "--size") std::sscanf(argv[3], "%dx%d", &width, &height);
  try {
    using namespace obscura::api;
    HeadlessContext context(HeadlessContext::Backend::Egl);
    Renderer renderer({context.getProcAddress(), true});
    renderer.clearScene();  // Obscura draws no scene of its own here
    renderer.set("ao.radius", 0.6);

    // The engine's scene: a floor and three boxes on it.
    const float grey[3] = {0.8f, 0.8f, 0.78f}, red[3] = {0.8f, 0.3f, 0.25f}, blue[3] = {0.3f, 0.45f, 0.8f};
    const float floorLo[3] = {-6, -0.1f, -6}, floorHi[3] = {6, 0, 6};
    const float box1Lo[3] = {-1.5f, 0, -1}, box1Hi[3] = {-0.5f, 1, 0};
    const float box2Lo[3] = {0.2f, 0, -1.5f}, box2Hi[3] = {1.4f, 1.8f, -0.3f};
    const float box3Lo[3] = {0.6f, 0, 0.8f}, box3Hi[3] = {1.2f, 0.6f, 1.4f};
    const std::vector<Mesh> meshes = {makeBox(floorLo, floorHi, grey), makeBox(box1Lo, box1Hi, red),
                                      makeBox(box2Lo, box2Hi, blue), makeBox(box3Lo, box3Hi, grey)};

    Camera camera;
    const float eye[3] = {2.5f, 2.6f, 4.5f}, target[3] = {0, 0.4f, -0.3f}, up[3] = {0, 1, 0};
    for (int i = 0; i < 3; ++i) {
      camera.eye[i] = eye[i];
      camera.target[i] = target[i];
      camera.up[i] = up[i];
    }
    camera.fovyDegrees = 50.0f;
    camera.near = 0.1f;
    camera.far = 30.0f;
    const Mat4 view = lookAt(eye, target, up);
    const Mat4 projection = perspective(camera.fovyDegrees, static_cast<float>(width) / static_cast<float>(height),
                                        camera.near, camera.far);

    // Its G-buffer shader: precision, Obscura's chunk (from the installed package), its own main().
    const std::string chunk = readFile(std::string(OBSCURA_GLSL_DIR) + "/obscura_gbuffer.glsl");
    if (chunk != gbufferGlsl()) throw std::runtime_error("the installed chunk is not the library's");
    const GLuint gbufferProgram = link(kVertex, "precision highp float;\n" + chunk + kGBufferMain);
    const GLuint colorProgram = link(kVertex, kColorFragment);

    // Its own colour framebuffer.
    GLuint colorTexture = 0, depth = 0, colorFramebuffer = 0;
    glGenTextures(1, &colorTexture);
    glBindTexture(GL_TEXTURE_2D, colorTexture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glGenFramebuffers(1, &colorFramebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, colorFramebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colorTexture, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("colour framebuffer incomplete");

    // 1. The G-buffer, into Obscura's framebuffer, with the engine's meshes and shader.
    renderer.beginGBuffer(width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(gbufferProgram);
    glUniform1f(glGetUniformLocation(gbufferProgram, "u_near"), camera.near);
    glUniform1f(glGetUniformLocation(gbufferProgram, "u_far"), camera.far);
    drawMeshes(gbufferProgram, meshes, view, projection);

    // 2. The engine's own lit colour.
    glBindFramebuffer(GL_FRAMEBUFFER, colorFramebuffer);
    glViewport(0, 0, width, height);
    glClearColor(0.62f, 0.74f, 0.9f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    drawMeshes(colorProgram, meshes, view, projection);
    glDisable(GL_DEPTH_TEST);

    // 3. Obscura's AO, multiplied into the engine's colour.
    const unsigned int aoTexture = renderer.ambientOcclusion(camera);
    renderer.compositeAmbientOcclusion({colorFramebuffer, width, height});

    // Read the result and the AO back (the AO through a debug view into a framebuffer of Obscura's).
    std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, colorFramebuffer);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    std::vector<std::uint8_t> image(pixels.size());
    for (int y = 0; y < height; ++y)  // GL rows are bottom-up, PNG rows top-down
      std::copy(pixels.begin() + static_cast<long>(y) * width * 4,
                pixels.begin() + static_cast<long>(y + 1) * width * 4,
                image.begin() + static_cast<long>(height - 1 - y) * width * 4);
    writePng(argv[1], width, height, image);
    OffscreenFramebuffer aoView(width, height);
    renderer.renderView("ao", camera, renderer.gbuffer(), aoView.framebuffer());
    const std::vector<std::uint8_t> ao = aoView.readRgba();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);

    // Where box 1 stands on the floor (its +z face's foot) and an open patch of floor in front.
    const Mat4 viewProjection = multiply(projection, view);
    const float contact[3] = {-1.0f, 0.02f, 0.06f}, open[3] = {-0.6f, 0.0f, 2.2f};
    int cx = 0, cy = 0, ox = 0, oy = 0;
    project(viewProjection, contact, width, height, &cx, &cy);
    project(viewProjection, open, width, height, &ox, &oy);
    if (cx < 0 || cy < 0 || ox < 0 || oy < 0 || cx >= width || ox >= width || oy >= height ||
        cy >= height)
      throw std::runtime_error("the probe points are off screen");
    auto visibility = [&](int x, int y) { return ao[(static_cast<std::size_t>(y) * width + x) * 4] / 255.0; };
    const double atContact = visibility(cx, cy), inTheOpen = visibility(ox, oy);
    const Stats stats = renderer.stats();
    std::printf("own_geometry: AO texture %u; visibility %.3f where a box meets the floor (%d, %d), %.3f on open "
                "floor (%d, %d); passes:", aoTexture, atContact, cx, cy, inTheOpen, ox, oy);
    for (const std::string& pass : stats.passesRun) std::printf(" %s", pass.c_str());
    std::printf("\nwrote %s\n", argv[1]);
    if (!(inTheOpen > 0.9 && atContact < inTheOpen - 0.15)) {
      std::fprintf(stderr, "own_geometry: the AO does not darken the contact against the open floor\n");
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "own_geometry: %s\n", e.what());
    return 1;
  }
  return 0;
}
