#include "reference/AoReferenceTracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "base/Error.h"
#include "encoding/LinearDepthPacking.h"
#include "reference/HemisphereSampling.h"

namespace obscura {
namespace {

namespace hs = HemisphereSampling;

// Hits a geometry rejects, as the raster passes would not draw them there:
// - back faces of single-sided materials, for primary rays (the rasteriser culls them; GpuScene). Embree's geometric
//   normal points out of the side from which the vertices appear counter-clockwise (the glTF and GL front face), so
//   a back face is one whose normal points along the ray;
// - alphaMode MASK cut-outs, for every ray (lib/material.glsl discards them in both geometry passes): where
//   baseColorFactor.a times the base-colour texture's alpha at the interpolated TEXCOORD_0 is below the cutoff.
//   The texture is sampled with its sampler's magnification filter and wrap modes on the original image; the GPU's
//   mipmaps (and the power-of-two resampling WebGL 1 needs for repeat or mipmaps) are not modelled, so at a cut-out's
//   edge a pixel may differ.
struct SurfaceFilter {
  bool cullBackFaces = false;
  bool alphaMask = false;
  float factorAlpha = 1.0f, cutoff = 0.5f;
  std::vector<std::uint32_t> indices;  // as in Embree's index buffer (winding swapped for mirroring transforms)
  std::vector<glm::vec2> texcoords;    // TEXCOORD_0 per vertex; empty: (0, 0) everywhere
  Image image;                         // the base-colour texture's image; empty: none
  SamplerState sampler;

  static int wrap(int i, int size, int mode) {
    if (mode == 0x812F) return std::clamp(i, 0, size - 1);  // GL_CLAMP_TO_EDGE
    if (mode == 0x8370) {                                      // GL_MIRRORED_REPEAT
      const int m = ((i % (2 * size)) + 2 * size) % (2 * size);
      return m < size ? m : 2 * size - 1 - m;
    }
    return ((i % size) + size) % size;  // GL_REPEAT
  }
  float texelAlpha(int x, int y) const {
    const size_t index = static_cast<size_t>(wrap(y, image.height, sampler.wrapT)) * image.width +
                         static_cast<size_t>(wrap(x, image.width, sampler.wrapS));
    return image.rgba[index * 4 + 3] / 255.0f;
  }
  float textureAlpha(const glm::vec2& uv) const {
    // Image row 0 is v = 0 (glTF's texture coordinates start at the image's top left).
    const float x = uv.x * static_cast<float>(image.width), y = uv.y * static_cast<float>(image.height);
    if (sampler.magFilter == 0x2600)  // GL_NEAREST
      return texelAlpha(static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y)));
    const float fx = x - 0.5f, fy = y - 0.5f;
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
    const float tx = fx - static_cast<float>(x0), ty = fy - static_cast<float>(y0);
    const float top = texelAlpha(x0, y0) * (1.0f - tx) + texelAlpha(x0 + 1, y0) * tx;
    const float bottom = texelAlpha(x0, y0 + 1) * (1.0f - tx) + texelAlpha(x0 + 1, y0 + 1) * tx;
    return top * (1.0f - ty) + bottom * ty;
  }
  // Embree's barycentrics: the hit is (1 - u - v) p0 + u p1 + v p2 of the triangle as stored.
  bool cutOut(unsigned triangle, float u, float v) const {
    float alpha = factorAlpha;
    if (!image.rgba.empty()) {
      // Without TEXCOORD_0 every vertex samples (0, 0), as GpuScene uploads it.
      glm::vec2 uv(0.0f);
      if (!texcoords.empty()) {
        const std::uint32_t* corner = &indices[3 * static_cast<size_t>(triangle)];
        uv = (1.0f - u - v) * texcoords[corner[0]] + u * texcoords[corner[1]] + v * texcoords[corner[2]];
      }
      alpha *= textureAlpha(uv);
    }
    return alpha < cutoff;
  }
  // cutOut() for hit i of a filter call.
  bool cutOutHit(const RTCFilterFunctionNArguments* args, unsigned i) const {
    return cutOut(RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                  RTCHitN_v(args->hit, args->N, i));
  }
};

void filterPrimaryHits(const RTCFilterFunctionNArguments* args) {
  const auto* filter = static_cast<const SurfaceFilter*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const float facing = RTCHitN_Ng_x(args->hit, args->N, i) * RTCRayN_dir_x(args->ray, args->N, i) +
                         RTCHitN_Ng_y(args->hit, args->N, i) * RTCRayN_dir_y(args->ray, args->N, i) +
                         RTCHitN_Ng_z(args->hit, args->N, i) * RTCRayN_dir_z(args->ray, args->N, i);
    if ((filter->cullBackFaces && facing > 0.0f) || (filter->alphaMask && filter->cutOutHit(args, i)))
      args->valid[i] = 0;
  }
}

void filterOcclusionHits(const RTCFilterFunctionNArguments* args) {
  const auto* filter = static_cast<const SurfaceFilter*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] == -1 && filter->cutOutHit(args, i)) args->valid[i] = 0;
}

void reportEmbreeError(void*, RTCError code, const char* message) {
  // Errors surface through rtcGetDeviceError below; this only keeps Embree from printing to stderr itself.
  (void)code;
  (void)message;
}

void throwOnDeviceError(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("Embree failed while ") + what + " (error " +
                             std::to_string(static_cast<int>(error)) + ")");
}

bool isPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }

int log2Exact(int n) {
  int log = 0;
  while ((1 << log) < n) ++log;
  return log;
}

}  // namespace

struct AoReferenceTracer::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<std::unique_ptr<SurfaceFilter>> filters;  // the geometries' user data, alive as long as the scene

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  // Fraction of cosine-distributed rays from `origin` around `normal` that travel `radius` without a hit.
  float visibility(const glm::vec3& origin, const glm::vec3& normal, const ReferenceSettings& settings,
                   std::uint32_t pixelX, std::uint32_t pixelY) const {
    glm::vec3 tangent, bitangent;
    hs::orthonormalBasis(normal, &tangent, &bitangent);
    // Two independent per-pixel digital shifts (one per coordinate) from the pixel position.
    const std::uint32_t seed = hs::hash32(pixelX * 0x9e3779b9U ^ hs::hash32(pixelY + 0x6a09e667U));
    const std::uint32_t shiftX = hs::hash32(seed ^ 0x85ebca6bU), shiftY = hs::hash32(seed ^ 0xc2b2ae35U);
    const int log2Rays = log2Exact(settings.rays);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    int unblocked = 0;
    for (int i = 0; i < settings.rays; ++i) {
      const glm::vec3 local =
          hs::cosineHemisphere(hs::shiftedHammersley(static_cast<std::uint32_t>(i), log2Rays, shiftX, shiftY));
      const glm::vec3 direction = local.x * tangent + local.y * bitangent + local.z * normal;
      RTCRay ray{};
      ray.org_x = origin.x;
      ray.org_y = origin.y;
      ray.org_z = origin.z;
      ray.dir_x = direction.x;
      ray.dir_y = direction.y;
      ray.dir_z = direction.z;
      ray.tnear = 0.0f;
      ray.tfar = settings.radius;
      ray.mask = 0xffffffffU;
      rtcOccluded1(scene, &context, &ray);
      // rtcOccluded1 sets tfar to -inf when something blocks the ray.
      unblocked += ray.tfar >= 0.0f;
    }
    return static_cast<float>(unblocked) / static_cast<float>(settings.rays);
  }
};

void validateReferenceSettings(const ReferenceSettings& settings) {
  if (!(settings.radius >= 1e-4f && settings.radius <= 1e6f))
    throw InputError("radius: " + std::to_string(settings.radius) + " is out of range (1e-4 .. 1e6 scene units)");
  if (!isPowerOfTwo(settings.rays) || settings.rays > 65536)
    throw InputError("rays: " + std::to_string(settings.rays) +
                     " must be a power of two in 1 .. 65536 (the sample set is a base-2 net)");
  if (settings.threads < 1 || settings.threads > 256)
    throw InputError("threads: " + std::to_string(settings.threads) + " is out of range (1 .. 256)");
}

AoReferenceTracer::AoReferenceTracer(const Scene& scene, int buildThreads) : impl_(std::make_unique<Impl>()) {
  const std::string config = "threads=" + std::to_string(std::max(1, buildThreads));
  impl_->device = rtcNewDevice(config.c_str());
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device");
  rtcSetDeviceErrorFunction(impl_->device, reportEmbreeError, nullptr);
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);

  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    if (mesh.indices.empty()) continue;
    const Material* material = mesh.material >= 0 ? &scene.materials[static_cast<size_t>(mesh.material)] : nullptr;
    const bool doubleSided = material && material->doubleSided;
    // A mirroring transform reverses the winding; swapping two indices keeps "front" the side GpuScene draws.
    const bool mirrored = glm::determinant(glm::mat3(instance.world)) < 0.0f;

    RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                 RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                 mesh.positions.size()));
    auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), mesh.indices.size() / 3));
    throwOnDeviceError(impl_->device, "allocating geometry buffers");
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::vec4 p = instance.world * glm::vec4(mesh.positions[v], 1.0f);
      vertices[3 * v + 0] = p.x;
      vertices[3 * v + 1] = p.y;
      vertices[3 * v + 2] = p.z;
    }
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      indices[t + 0] = mesh.indices[t + 0];
      indices[t + 1] = mesh.indices[t + (mirrored ? 2 : 1)];
      indices[t + 2] = mesh.indices[t + (mirrored ? 1 : 2)];
    }
    // Filters only where needed: opaque double-sided geometry keeps Embree's full speed.
    auto filter = std::make_unique<SurfaceFilter>();
    filter->cullBackFaces = !doubleSided;
    filter->alphaMask = material && material->alphaMode == AlphaMode::Mask;
    if (filter->alphaMask) {
      filter->factorAlpha = material->baseColorFactor.a;
      filter->cutoff = material->alphaCutoff;
      filter->indices.assign(indices, indices + mesh.indices.size() / 3 * 3);
      filter->texcoords = mesh.texcoords;
      if (material->baseColorTexture >= 0) {
        const Texture& texture = scene.textures[static_cast<size_t>(material->baseColorTexture)];
        filter->sampler = texture.sampler;
        if (texture.image >= 0) filter->image = scene.images[static_cast<size_t>(texture.image)];
      }
      rtcSetGeometryOccludedFilterFunction(geometry, filterOcclusionHits);
    }
    if (filter->cullBackFaces || filter->alphaMask) {
      rtcSetGeometryIntersectFilterFunction(geometry, filterPrimaryHits);
      rtcSetGeometryUserData(geometry, filter.get());
      impl_->filters.push_back(std::move(filter));
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(impl_->scene, geometry);
    rtcReleaseGeometry(geometry);
    triangles_ += mesh.indices.size() / 3;
  }
  rtcCommitScene(impl_->scene);
  throwOnDeviceError(impl_->device, "building the scene");
}

AoReferenceTracer::~AoReferenceTracer() = default;

float AoReferenceTracer::visibilityAt(const glm::vec3& point, const glm::vec3& normal,
                                      const ReferenceSettings& settings, std::uint32_t pixelX,
                                      std::uint32_t pixelY) const {
  validateReferenceSettings(settings);
  const glm::vec3 n = glm::normalize(normal);
  const float scale = std::max({std::abs(point.x), std::abs(point.y), std::abs(point.z), 1e-3f});
  return impl_->visibility(point + n * (2e-5f * scale), n, settings, pixelX, pixelY);
}

ReferenceFrame AoReferenceTracer::trace(const Camera& camera, const ReferenceSettings& settings) const {
  validateReferenceSettings(settings);
  camera.validate("camera");
  ReferenceFrame frame;
  frame.width = camera.width;
  frame.height = camera.height;
  const size_t pixelCount = static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height);
  frame.visibility.assign(pixelCount, 1.0f);
  frame.linearDepth.assign(pixelCount, 1.0f);
  frame.mask.assign(pixelCount, 0);

  const glm::mat4 viewToWorld = glm::inverse(camera.view());
  const glm::mat3 rotation(viewToWorld);
  const glm::vec2 halfExtent = camera.halfExtent(camera.aspect());  // as the rasteriser's projection has it

  auto tracePixel = [&](int x, int y, const RTCIntersectContext& contextTemplate) {
    // The view-space direction has z = -1, so the hit distance t along it is the view depth -z_view, and the
    // rasteriser's near/far clipping becomes t in [near, far]: from the eye through the pixel in perspective; from
    // the pixel's point of the eye's plane, along the view axis, in orthographic projection.
    const float ndcX = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(camera.width) - 1.0f;
    const float ndcY = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(camera.height);
    const glm::vec2 onScreen = glm::vec2(ndcX, ndcY) * halfExtent;
    const glm::vec3 origin =
        camera.orthographic ? camera.eye + rotation * glm::vec3(onScreen, 0.0f) : camera.eye;
    const glm::vec3 direction =
        rotation * (camera.orthographic ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(onScreen, -1.0f));
    RTCIntersectContext context = contextTemplate;
    RTCRayHit hit{};
    hit.ray.org_x = origin.x;
    hit.ray.org_y = origin.y;
    hit.ray.org_z = origin.z;
    hit.ray.dir_x = direction.x;
    hit.ray.dir_y = direction.y;
    hit.ray.dir_z = direction.z;
    hit.ray.tnear = camera.near;
    hit.ray.tfar = camera.far;
    hit.ray.mask = 0xffffffffU;
    hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &context, &hit);
    if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return;
    const float depth = (hit.ray.tfar - camera.near) / (camera.far - camera.near);
    // The G-buffer treats geometry that rounds to the last depth code as background; so does the reference.
    if (LinearDepthPacking::codeFromDepth(depth) == LinearDepthPacking::kBackgroundCode) return;

    glm::vec3 normal = glm::normalize(glm::vec3(hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z));
    if (glm::dot(normal, direction) > 0.0f) normal = -normal;  // face the viewer
    const glm::vec3 point = origin + direction * hit.ray.tfar;
    // Offset against self-intersection: a few hundred ulps of the coordinates' magnitude.
    const float scale = std::max({std::abs(point.x), std::abs(point.y), std::abs(point.z), hit.ray.tfar, 1e-3f});
    const size_t index = static_cast<size_t>(y) * static_cast<size_t>(camera.width) + static_cast<size_t>(x);
    frame.linearDepth[index] = depth;
    frame.mask[index] = 1;
    frame.visibility[index] = impl_->visibility(point + normal * (2e-5f * scale), normal, settings,
                                                static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
  };

  // Rows are handed out one at a time; each pixel's result depends only on its coordinates, so the image is the
  // same for any number of threads.
  std::atomic<int> nextRow{0};
  auto worker = [&] {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (int y = nextRow++; y < camera.height; y = nextRow++)
      for (int x = 0; x < camera.width; ++x) tracePixel(x, y, context);
  };
  std::vector<std::thread> workers;
  for (int t = 1; t < settings.threads; ++t) workers.emplace_back(worker);
  worker();
  for (std::thread& t : workers) t.join();
  return frame;
}

namespace {
Image greyImage(int width, int height, const std::vector<float>& values) {
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.resize(values.size() * 4);
  for (size_t i = 0; i < values.size(); ++i) {
    // Rounded to nearest, as GL converts a float colour to an 8-bit channel.
    const auto grey = static_cast<std::uint8_t>(std::lround(std::clamp(values[i], 0.0f, 1.0f) * 255.0f));
    image.rgba[4 * i + 0] = image.rgba[4 * i + 1] = image.rgba[4 * i + 2] = grey;
    image.rgba[4 * i + 3] = 255;
  }
  return image;
}
}  // namespace

Image ReferenceFrame::aoImage() const { return greyImage(width, height, visibility); }

Image ReferenceFrame::depthImage() const {
  // obscura-render's depth view shows the 16-bit code the G-buffer stores, code / 65535, as grey.
  std::vector<float> shown(linearDepth.size());
  for (size_t i = 0; i < shown.size(); ++i)
    shown[i] = LinearDepthPacking::depthFromCode(LinearDepthPacking::codeFromDepth(linearDepth[i]));
  return greyImage(width, height, shown);
}

Image ReferenceFrame::maskImage() const {
  std::vector<float> shown(mask.size());
  for (size_t i = 0; i < shown.size(); ++i) shown[i] = mask[i] ? 1.0f : 0.0f;
  return greyImage(width, height, shown);
}

}  // namespace obscura
