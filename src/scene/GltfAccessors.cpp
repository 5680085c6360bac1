#include <algorithm>
#include <cmath>
#include <cstring>

#include "scene/GltfCompression.h"
#include "scene/GltfReading.h"

namespace obscura::gltf {

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

const char* componentTypeName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "an invalid component type";
  }
}

namespace {

// Reads component `c` of a tightly described element as a double, applying glTF's normalisation rules.
double readComponent(const std::uint8_t* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: return 0.0;
  }
}

// The bytes a buffer view covers, after checking that it lies inside its buffer.
const std::uint8_t* bufferViewData(const LoaderContext& ctx, int viewIndex, const std::string& what,
                                   std::uint64_t* length) {
  const auto& views = ctx.model.bufferViews;
  if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= views.size())
    ctx.refuse(what + " refers to bufferView " + std::to_string(viewIndex) + ", which does not exist");
  const tinygltf::BufferView& view = views[static_cast<size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= ctx.model.buffers.size())
    ctx.refuse("bufferView " + std::to_string(viewIndex) + " refers to buffer " + std::to_string(view.buffer) +
               ", which does not exist");
  const tinygltf::Buffer& buffer = ctx.model.buffers[static_cast<size_t>(view.buffer)];
  const std::uint64_t end = std::uint64_t(view.byteOffset) + std::uint64_t(view.byteLength);
  if (end > buffer.data.size())
    ctx.refuse("bufferView " + std::to_string(viewIndex) + " spans bytes " + std::to_string(view.byteOffset) + ".." +
               std::to_string(end) + " but buffer " + std::to_string(view.buffer) + " holds " +
               std::to_string(buffer.data.size()) + " bytes" +
               (buffer.data.empty() ? " (is its .bin file missing?)" : ""));
  *length = view.byteLength;
  return buffer.data.data() + view.byteOffset;
}

}  // namespace

std::vector<double> readAccessor(const LoaderContext& ctx, int accessorIndex, const std::string& use, int components,
                                 const std::vector<int>& allowed) {
  const auto& accessors = ctx.model.accessors;
  if (accessorIndex < 0 || static_cast<size_t>(accessorIndex) >= accessors.size())
    ctx.refuse(use + " refers to accessor " + std::to_string(accessorIndex) + ", which does not exist");
  const tinygltf::Accessor& a = accessors[static_cast<size_t>(accessorIndex)];
  const std::string what = use + " (accessor " + std::to_string(accessorIndex) + ")";
  if (componentCount(a.type) != components)
    ctx.refuse(what + " has " + std::to_string(componentCount(a.type)) + " components per element, expected " +
               std::to_string(components));
  if (std::find(allowed.begin(), allowed.end(), a.componentType) == allowed.end())
    ctx.refuse(what + " has component type " + componentTypeName(a.componentType) + ", which glTF does not allow here");
  if (a.count > ctx.limits.maxAccessorElements)
    ctx.refuse(what + " has " + std::to_string(a.count) + " elements, over the limit of " +
               std::to_string(ctx.limits.maxAccessorElements));

  const int size = componentSize(a.componentType);
  const std::uint64_t elementSize = std::uint64_t(size) * components;
  // Every bound is checked before anything is allocated: a small file declaring a huge count over a short buffer is
  // refused at once, not after reserving memory for the count.
  const std::uint8_t* data = nullptr;
  std::uint64_t stride = elementSize;
  if (a.bufferView >= 0) {
    std::uint64_t viewLength = 0;
    data = bufferViewData(ctx, a.bufferView, what, &viewLength);
    const tinygltf::BufferView& view = ctx.model.bufferViews[static_cast<size_t>(a.bufferView)];
    if (view.byteStride && (view.byteStride < elementSize || view.byteStride > 252 || view.byteStride % 4 != 0))
      ctx.refuse(what + " has byteStride " + std::to_string(view.byteStride) + ", expected a multiple of 4 in " +
                 std::to_string(elementSize) + " .. 252");
    if (view.byteStride) stride = view.byteStride;
    if (a.count > 0) {
      const std::uint64_t last = std::uint64_t(a.byteOffset) + stride * (a.count - 1) + elementSize;
      if (last > viewLength)
        ctx.refuse(what + " reads up to byte " + std::to_string(last) + " of bufferView " +
                   std::to_string(a.bufferView) + ", which holds " + std::to_string(viewLength));
    }
  }

  std::vector<double> out(a.count * static_cast<size_t>(components), 0.0);
  if (data) {
    for (size_t i = 0; i < a.count; ++i) {
      const std::uint8_t* element = data + a.byteOffset + stride * i;
      for (int c = 0; c < components; ++c)
        out[i * components + c] = readComponent(element + c * size, a.componentType, a.normalized);
    }
  }

  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    if (s.count < 0 || static_cast<size_t>(s.count) > a.count)
      ctx.refuse(what + " has a sparse count of " + std::to_string(s.count) + " for " + std::to_string(a.count) +
                 " elements");
    const int indexSize = componentSize(s.indices.componentType);
    if (s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      ctx.refuse(what + " has sparse indices of component type " + componentTypeName(s.indices.componentType));
    std::uint64_t indexViewLength = 0, valueViewLength = 0;
    const std::uint8_t* indexData =
        bufferViewData(ctx, s.indices.bufferView, what + " sparse indices", &indexViewLength);
    const std::uint8_t* valueData = bufferViewData(ctx, s.values.bufferView, what + " sparse values", &valueViewLength);
    if (s.indices.byteOffset < 0 || s.values.byteOffset < 0 ||
        std::uint64_t(s.indices.byteOffset) + std::uint64_t(indexSize) * s.count > indexViewLength ||
        std::uint64_t(s.values.byteOffset) + elementSize * s.count > valueViewLength)
      ctx.refuse(what + " has sparse data outside its buffer views");
    for (int k = 0; k < s.count; ++k) {
      const double target = readComponent(indexData + s.indices.byteOffset + std::uint64_t(k) * indexSize,
                                          s.indices.componentType, false);
      if (target < 0 || target >= static_cast<double>(a.count))
        ctx.refuse(what + " has sparse index " + std::to_string(static_cast<std::uint64_t>(target)) +
                   " outside its " + std::to_string(a.count) + " elements");
      const std::uint8_t* element = valueData + s.values.byteOffset + elementSize * std::uint64_t(k);
      for (int c = 0; c < components; ++c)
        out[static_cast<size_t>(target) * components + c] = readComponent(element + c * size, a.componentType,
                                                                          a.normalized);
    }
  }
  return out;
}

std::vector<double> readVertexAttribute(const LoaderContext& ctx, int accessorIndex, const std::string& what,
                                        int components, const char* use) {
  const AttributeTypes types = quantizedAttributeTypes(use, usesMeshQuantization(ctx.model));
  std::vector<double> values = readAccessor(ctx, accessorIndex, what, components, types.allowed);
  const tinygltf::Accessor& accessor = ctx.model.accessors[static_cast<size_t>(accessorIndex)];
  if (!accessor.normalized && std::find(types.normalizedOnly.begin(), types.normalizedOnly.end(),
                                        accessor.componentType) != types.normalizedOnly.end())
    ctx.refuse(what + " (accessor " + std::to_string(accessorIndex) + ") has component type " +
               componentTypeName(accessor.componentType) + " without normalized: true, which glTF does not allow");
  return values;
}

int attributeAccessor(const tinygltf::Primitive& primitive, const char* name) {
  auto it = primitive.attributes.find(name);
  return it == primitive.attributes.end() ? -1 : it->second;
}

bool allFinite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
}

}  // namespace obscura::gltf
