#include <algorithm>
#include <cmath>

#include "scene/GltfReading.h"

namespace obscura::gltf {
namespace {

// KHR_texture_transform on one texture, as the matrix that maps TEXCOORD_0 to the coordinates sampled:
// uv' = T(offset) * R(rotation) * S(scale) * uv. The extension's README lists R as the usual counter-clockwise matrix,
// but in glTF's UV space (v pointing down) the sample model TextureTransformTest, Babylon.js and three.js all use
// u' = cos r u + sin r v, v' = -sin r u + cos r v (KhronosGroup/glTF issue #1563); so does this.
// Identity when the texture has no such extension. Scales and offsets that are not finite are refused.
glm::mat3 uvTransform(const LoaderContext& ctx, int textureIndex, const tinygltf::ExtensionMap& extensions,
                      const std::string& what) {
  const auto it = extensions.find("KHR_texture_transform");
  if (textureIndex < 0 || it == extensions.end() || !it->second.IsObject()) return glm::mat3(1.0f);
  const tinygltf::Value& transform = it->second;
  auto pair = [&](const char* key, glm::vec2 fallback) {
    if (!transform.Has(key)) return fallback;
    const tinygltf::Value& v = transform.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
      ctx.refuse(what + ": KHR_texture_transform " + key + " is not an array of two numbers");
    return glm::vec2(static_cast<float>(v.Get(0).GetNumberAsDouble()),
                     static_cast<float>(v.Get(1).GetNumberAsDouble()));
  };
  const glm::vec2 offset = pair("offset", glm::vec2(0.0f)), scale = pair("scale", glm::vec2(1.0f));
  float rotation = 0.0f;
  if (transform.Has("rotation")) {
    if (!transform.Get("rotation").IsNumber()) ctx.refuse(what + ": KHR_texture_transform rotation is not a number");
    rotation = static_cast<float>(transform.Get("rotation").GetNumberAsDouble());
  }
  if (!std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(scale.x) || !std::isfinite(scale.y) ||
      !std::isfinite(rotation))
    ctx.refuse(what + ": KHR_texture_transform has a value that is not finite");
  const int texCoord = transform.Has("texCoord") && transform.Get("texCoord").IsInt()
                           ? transform.Get("texCoord").GetNumberAsInt()
                           : 0;
  if (texCoord != 0)
    ctx.report.warnings.push_back(what + ": KHR_texture_transform asks for TEXCOORD_" + std::to_string(texCoord) +
                                  ", only TEXCOORD_0 is read");
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::mat3 translationMatrix(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);  // columns
  const glm::mat3 rotationMatrix(c, -s, 0, s, c, 0, 0, 0, 1);
  const glm::mat3 scaleMatrix(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return translationMatrix * rotationMatrix * scaleMatrix;
}

// The material samples textures besides the base colour (Material::hasPbrTextures): its slots' transforms then go to
// the vertex stage, and the base colour's is not baked into TEXCOORD_0.
bool hasPbrTextures(const tinygltf::Material& m) {
  // As loadMaterials keeps them: a slot on another TEXCOORD is ignored.
  auto used = [](int index, int texCoord) { return index >= 0 && texCoord == 0; };
  const auto& mr = m.pbrMetallicRoughness.metallicRoughnessTexture;
  return used(mr.index, mr.texCoord) || used(m.normalTexture.index, m.normalTexture.texCoord) ||
         used(m.occlusionTexture.index, m.occlusionTexture.texCoord) ||
         used(m.emissiveTexture.index, m.emissiveTexture.texCoord);
}

}  // namespace

const tinygltf::Material* materialOf(const LoaderContext& ctx, int materialIndex) {
  if (materialIndex < 0 || static_cast<size_t>(materialIndex) >= ctx.model.materials.size()) return nullptr;
  return &ctx.model.materials[static_cast<size_t>(materialIndex)];
}

glm::mat3 baseColorUvTransform(const LoaderContext& ctx, int materialIndex, const std::string& what) {
  const tinygltf::Material* material = materialOf(ctx, materialIndex);
  if (!material || hasPbrTextures(*material)) return glm::mat3(1.0f);
  const tinygltf::TextureInfo& info = material->pbrMetallicRoughness.baseColorTexture;
  return uvTransform(ctx, info.index, info.extensions, what);
}

void loadMaterials(const LoaderContext& ctx, Scene& scene) {
  const tinygltf::Model& model = ctx.model;
  for (const tinygltf::Image& source : model.images) {
    Image image;
    if (!source.image.empty() && source.width > 0 && source.height > 0 && source.component == 4 && source.bits == 8 &&
        source.image.size() == size_t(source.width) * source.height * 4) {
      image.width = source.width;
      image.height = source.height;
      image.rgba = source.image;
    } else {
      ctx.report.warnings.push_back("image '" + (source.name.empty() ? source.uri : source.name) +
                                    "' could not be decoded; its texture is drawn white");
    }
    scene.images.push_back(std::move(image));
  }
  for (const tinygltf::Texture& source : model.textures) {
    Texture texture;
    if (source.source >= 0 && static_cast<size_t>(source.source) < scene.images.size() &&
        scene.images[static_cast<size_t>(source.source)].width > 0)
      texture.image = source.source;
    if (source.sampler >= 0 && static_cast<size_t>(source.sampler) < model.samplers.size()) {
      const tinygltf::Sampler& s = model.samplers[static_cast<size_t>(source.sampler)];
      if (s.magFilter > 0) texture.sampler.magFilter = s.magFilter;
      if (s.minFilter > 0) texture.sampler.minFilter = s.minFilter;
      texture.sampler.wrapS = s.wrapS;
      texture.sampler.wrapT = s.wrapT;
    }
    scene.textures.push_back(texture);
  }
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& source = model.materials[i];
    Material material;
    material.metallicFactor = 1.0f;  // glTF's defaults (a Material made in code is a dielectric)
    material.roughnessFactor = 1.0f;
    const auto& factor = source.pbrMetallicRoughness.baseColorFactor;
    if (factor.size() == 4 && std::all_of(factor.begin(), factor.end(), [](double v) { return std::isfinite(v); }))
      material.baseColorFactor = glm::clamp(glm::vec4(factor[0], factor[1], factor[2], factor[3]), 0.0f, 1.0f);
    const auto& textureInfo = source.pbrMetallicRoughness.baseColorTexture;
    if (textureInfo.index >= 0) {
      if (static_cast<size_t>(textureInfo.index) >= scene.textures.size())
        ctx.refuse("material " + std::to_string(i) + " refers to texture " + std::to_string(textureInfo.index) +
                   ", which does not exist");
      if (textureInfo.texCoord == 0) material.baseColorTexture = textureInfo.index;
      else ctx.report.warnings.push_back("material " + std::to_string(i) + ": base colour uses TEXCOORD_" +
                                         std::to_string(textureInfo.texCoord) + ", only TEXCOORD_0 is read");
    }
    const std::string name = "material " + std::to_string(i);
    // A texture of another slot: checked, TEXCOORD_0 only, its KHR_texture_transform kept for the vertex stage.
    auto slot = [&](TextureSlot which, int index, int texCoord, const tinygltf::ExtensionMap& extensions,
                    const char* slotName) {
      if (index < 0) return -1;
      if (static_cast<size_t>(index) >= scene.textures.size())
        ctx.refuse(name + " refers to texture " + std::to_string(index) + ", which does not exist");
      if (texCoord != 0) {
        ctx.report.warnings.push_back(name + ": " + slotName + " uses TEXCOORD_" + std::to_string(texCoord) +
                                      ", only TEXCOORD_0 is read; the slot is ignored");
        return -1;
      }
      material.uvTransforms[static_cast<size_t>(which)] = uvTransform(ctx, index, extensions, name + " " + slotName);
      return index;
    };
    auto finite = [](double v, double fallback) { return std::isfinite(v) ? v : fallback; };
    const auto& pbr = source.pbrMetallicRoughness;
    material.metallicFactor = static_cast<float>(std::clamp(finite(pbr.metallicFactor, 1.0), 0.0, 1.0));
    material.roughnessFactor = static_cast<float>(std::clamp(finite(pbr.roughnessFactor, 1.0), 0.0, 1.0));
    material.metallicRoughnessTexture =
        slot(TextureSlot::MetallicRoughness, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
             pbr.metallicRoughnessTexture.extensions, "metallicRoughnessTexture");
    material.normalTexture = slot(TextureSlot::Normal, source.normalTexture.index, source.normalTexture.texCoord,
                                  source.normalTexture.extensions, "normalTexture");
    material.normalScale = static_cast<float>(finite(source.normalTexture.scale, 1.0));
    material.occlusionTexture =
        slot(TextureSlot::Occlusion, source.occlusionTexture.index, source.occlusionTexture.texCoord,
             source.occlusionTexture.extensions, "occlusionTexture");
    material.occlusionStrength =
        static_cast<float>(std::clamp(finite(source.occlusionTexture.strength, 1.0), 0.0, 1.0));
    material.emissiveTexture = slot(TextureSlot::Emissive, source.emissiveTexture.index,
                                    source.emissiveTexture.texCoord, source.emissiveTexture.extensions,
                                    "emissiveTexture");
    if (source.emissiveFactor.size() == 3)
      material.emissiveFactor = glm::clamp(glm::vec3(finite(source.emissiveFactor[0], 0.0),
                                                     finite(source.emissiveFactor[1], 0.0),
                                                     finite(source.emissiveFactor[2], 0.0)),
                                           0.0f, 1.0f);
    const auto strength = source.extensions.find("KHR_materials_emissive_strength");
    if (strength != source.extensions.end() && strength->second.IsObject() &&
        strength->second.Has("emissiveStrength") && strength->second.Get("emissiveStrength").IsNumber()) {
      const double value = strength->second.Get("emissiveStrength").GetNumberAsDouble();
      if (!std::isfinite(value) || value < 0.0) ctx.refuse(name + ": emissiveStrength is negative or not finite");
      material.emissiveStrength = static_cast<float>(value);
    }
    // The base colour's transform: baked into TEXCOORD_0 (loadPrimitive) unless other slots need the coordinates.
    if (material.hasPbrTextures() && material.baseColorTexture >= 0)
      material.uvTransforms[0] =
          uvTransform(ctx, textureInfo.index, textureInfo.extensions, name + " baseColorTexture");
    if (source.alphaMode == "MASK") material.alphaMode = AlphaMode::Mask;
    else if (source.alphaMode == "BLEND") material.alphaMode = AlphaMode::Blend;
    material.alphaCutoff = std::isfinite(source.alphaCutoff) ? static_cast<float>(source.alphaCutoff) : 0.5f;
    material.doubleSided = source.doubleSided;
    scene.materials.push_back(material);
  }
}

}  // namespace obscura::gltf
