#include <algorithm>
#include <cmath>

#include "scene/GltfReading.h"

namespace obscura::gltf {
namespace {

// KHR_texture_transform on one texture, as the matrix that maps its TEXCOORD_n to the coordinates sampled:
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
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::mat3 translationMatrix(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);  // columns
  const glm::mat3 rotationMatrix(c, -s, 0, s, c, 0, 0, 0, 1);
  const glm::mat3 scaleMatrix(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return translationMatrix * rotationMatrix * scaleMatrix;
}

// The texture coordinate set a texture reference samples: KHR_texture_transform's texCoord, where given, overrides
// the reference's own (the extension's README).
int referenceTexCoord(int texCoord, const tinygltf::ExtensionMap& extensions) {
  const auto it = extensions.find("KHR_texture_transform");
  if (it != extensions.end() && it->second.IsObject() && it->second.Has("texCoord") &&
      it->second.Get("texCoord").IsInt())
    return it->second.Get("texCoord").GetNumberAsInt();
  return texCoord;
}

// Sets the loader reads: TEXCOORD_0 and TEXCOORD_1 (scene/Scene.h: Mesh::texcoords1).
bool readableTexCoord(int texCoord) { return texCoord == 0 || texCoord == 1; }

// The material samples textures besides the base colour (Material::hasPbrTextures): its slots' transforms then go to
// the vertex stage, and the base colour's is not baked into the mesh's coordinates.
bool hasPbrTextures(const tinygltf::Material& m) {
  // As loadMaterials keeps them: a slot on a set other than TEXCOORD_0 or _1 is ignored.
  auto used = [](const auto& info) {
    return info.index >= 0 && readableTexCoord(referenceTexCoord(info.texCoord, info.extensions));
  };
  return used(m.pbrMetallicRoughness.metallicRoughnessTexture) || used(m.normalTexture) ||
         used(m.occlusionTexture) || used(m.emissiveTexture);
}

double finite(double v, double fallback) { return std::isfinite(v) ? v : fallback; }

// A number of an extension object: `fallback` where absent; refused where present and not a finite number in
// [low, high].
float extensionNumber(const LoaderContext& ctx, const tinygltf::Value& extension, const char* key, double fallback,
                      double low, double high, const std::string& what) {
  if (!extension.Has(key)) return static_cast<float>(fallback);
  const tinygltf::Value& v = extension.Get(key);
  const double value = v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
  if (!(std::isfinite(value) && value >= low && value <= high))
    ctx.refuse(what + ": " + key + " is not a number in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
  return static_cast<float>(value);
}

// The material extensions Obscura shades (scene/Scene.h: Material), read from their objects. Their textures take
// no texture unit: the forward lighting of a material with every core texture already samples all eight that GLES 2
// guarantees (gpu/TextureUnits.h), so each is named in a warning and the factor alone applies.
void readMaterialExtensions(const LoaderContext& ctx, const tinygltf::Material& source, const std::string& name,
                            Material& material) {
  auto object = [&](const char* extension) -> const tinygltf::Value* {
    const auto it = source.extensions.find(extension);
    return it != source.extensions.end() && it->second.IsObject() ? &it->second : nullptr;
  };
  auto unreadTextures = [&](const tinygltf::Value& extension, const char* extensionName,
                            std::initializer_list<const char*> keys) {
    for (const char* key : keys)
      if (extension.Has(key))
        ctx.report.warnings.push_back(name + ": " + extensionName + " " + key +
                                      " not read (no texture unit left within GLES 2's eight); its factor applies");
  };
  if (object("KHR_materials_unlit")) material.unlit = true;
  if (const tinygltf::Value* e = object("KHR_materials_emissive_strength"))
    material.emissiveStrength = extensionNumber(ctx, *e, "emissiveStrength", 1.0, 0.0, 1e30, name);
  if (const tinygltf::Value* e = object("KHR_materials_ior")) {
    material.ior = extensionNumber(ctx, *e, "ior", 1.5, 0.0, 1e30, name);
    // The extension allows 0 (a legacy "infinite" index: Fresnel 1) or at least 1.
    if (material.ior > 0.0f && material.ior < 1.0f) ctx.refuse(name + ": ior is between 0 and 1");
  }
  if (const tinygltf::Value* e = object("KHR_materials_specular")) {
    material.specularFactor = extensionNumber(ctx, *e, "specularFactor", 1.0, 0.0, 1.0, name);
    if (e->Has("specularColorFactor")) {
      const tinygltf::Value& c = e->Get("specularColorFactor");
      if (!c.IsArray() || c.ArrayLen() != 3) ctx.refuse(name + ": specularColorFactor is not an array of three");
      for (int k = 0; k < 3; ++k) {
        const double v = c.Get(k).IsNumber() ? c.Get(k).GetNumberAsDouble() : -1.0;
        if (!(std::isfinite(v) && v >= 0.0)) ctx.refuse(name + ": specularColorFactor is negative or not finite");
        material.specularColorFactor[k] = static_cast<float>(v);
      }
    }
    unreadTextures(*e, "KHR_materials_specular", {"specularTexture", "specularColorTexture"});
  }
  if (const tinygltf::Value* e = object("KHR_materials_clearcoat")) {
    material.clearcoatFactor = extensionNumber(ctx, *e, "clearcoatFactor", 0.0, 0.0, 1.0, name);
    material.clearcoatRoughnessFactor = extensionNumber(ctx, *e, "clearcoatRoughnessFactor", 0.0, 0.0, 1.0, name);
    unreadTextures(*e, "KHR_materials_clearcoat",
                   {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"});
  }
  if (const tinygltf::Value* e = object("KHR_materials_transmission")) {
    material.transmissionFactor = extensionNumber(ctx, *e, "transmissionFactor", 0.0, 0.0, 1.0, name);
    unreadTextures(*e, "KHR_materials_transmission", {"transmissionTexture"});
  }
}

}  // namespace

const tinygltf::Material* materialOf(const LoaderContext& ctx, int materialIndex) {
  if (materialIndex < 0 || static_cast<size_t>(materialIndex) >= ctx.model.materials.size()) return nullptr;
  return &ctx.model.materials[static_cast<size_t>(materialIndex)];
}

BakedBaseColorUv baseColorUvToBake(const LoaderContext& ctx, int materialIndex, const std::string& what) {
  const tinygltf::Material* material = materialOf(ctx, materialIndex);
  if (!material || hasPbrTextures(*material)) return {};
  const tinygltf::TextureInfo& info = material->pbrMetallicRoughness.baseColorTexture;
  const int texCoord = referenceTexCoord(info.texCoord, info.extensions);
  if (info.index < 0 || !readableTexCoord(texCoord)) return {};
  return {uvTransform(ctx, info.index, info.extensions, what), texCoord};
}

int normalTextureTexCoord(const tinygltf::Material& material) {
  const int texCoord = referenceTexCoord(material.normalTexture.texCoord, material.normalTexture.extensions);
  return readableTexCoord(texCoord) ? texCoord : 0;
}

bool usesTexCoord1(const tinygltf::Material& m) {
  if (!hasPbrTextures(m)) return false;  // the base colour alone: baked into TEXCOORD_0
  auto onSet1 = [](const auto& info) {
    return info.index >= 0 && referenceTexCoord(info.texCoord, info.extensions) == 1;
  };
  return onSet1(m.pbrMetallicRoughness.baseColorTexture) || onSet1(m.pbrMetallicRoughness.metallicRoughnessTexture) ||
         onSet1(m.normalTexture) || onSet1(m.occlusionTexture) || onSet1(m.emissiveTexture);
}

int texCoordSetsSampled(const LoaderContext& ctx, int materialIndex) {
  const tinygltf::Material* m = materialOf(ctx, materialIndex);
  if (!m) return 0;
  int sets = 0;
  auto sampled = [&](const auto& info) {
    if (info.index < 0) return;
    const int texCoord = referenceTexCoord(info.texCoord, info.extensions);
    if (readableTexCoord(texCoord)) sets = std::max(sets, texCoord + 1);
  };
  sampled(m->pbrMetallicRoughness.baseColorTexture);
  sampled(m->pbrMetallicRoughness.metallicRoughnessTexture);
  sampled(m->normalTexture);
  sampled(m->occlusionTexture);
  sampled(m->emissiveTexture);
  return sets;
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
    const std::string name = "material " + std::to_string(i);
    // A slot's texture: checked, on TEXCOORD_0 or _1, its KHR_texture_transform kept for the vertex stage.
    auto slot = [&](TextureSlot which, const auto& info, const char* slotName) {
      if (info.index < 0) return -1;
      if (static_cast<size_t>(info.index) >= scene.textures.size())
        ctx.refuse(name + " refers to texture " + std::to_string(info.index) + ", which does not exist");
      const int texCoord = referenceTexCoord(info.texCoord, info.extensions);
      if (!readableTexCoord(texCoord)) {
        ctx.report.warnings.push_back(name + ": " + slotName + " uses TEXCOORD_" + std::to_string(texCoord) +
                                      ", only TEXCOORD_0 and TEXCOORD_1 are read; the slot is ignored");
        return -1;
      }
      material.texCoords[static_cast<size_t>(which)] = texCoord;
      material.uvTransforms[static_cast<size_t>(which)] =
          uvTransform(ctx, info.index, info.extensions, name + " " + slotName);
      return info.index;
    };
    const auto& pbr = source.pbrMetallicRoughness;
    material.baseColorTexture = slot(TextureSlot::BaseColor, pbr.baseColorTexture, "baseColorTexture");
    material.metallicFactor = static_cast<float>(std::clamp(finite(pbr.metallicFactor, 1.0), 0.0, 1.0));
    material.roughnessFactor = static_cast<float>(std::clamp(finite(pbr.roughnessFactor, 1.0), 0.0, 1.0));
    material.metallicRoughnessTexture =
        slot(TextureSlot::MetallicRoughness, pbr.metallicRoughnessTexture, "metallicRoughnessTexture");
    material.normalTexture = slot(TextureSlot::Normal, source.normalTexture, "normalTexture");
    material.normalScale = static_cast<float>(finite(source.normalTexture.scale, 1.0));
    material.occlusionTexture = slot(TextureSlot::Occlusion, source.occlusionTexture, "occlusionTexture");
    material.occlusionStrength =
        static_cast<float>(std::clamp(finite(source.occlusionTexture.strength, 1.0), 0.0, 1.0));
    material.emissiveTexture = slot(TextureSlot::Emissive, source.emissiveTexture, "emissiveTexture");
    if (source.emissiveFactor.size() == 3)
      material.emissiveFactor = glm::clamp(glm::vec3(finite(source.emissiveFactor[0], 0.0),
                                                     finite(source.emissiveFactor[1], 0.0),
                                                     finite(source.emissiveFactor[2], 0.0)),
                                           0.0f, 1.0f);
    readMaterialExtensions(ctx, source, name, material);
    // The base colour's coordinates are baked into the mesh's TEXCOORD_0 (loadPrimitive: baseColorUvToBake) unless
    // other slots need the coordinates; then the vertex stage transforms them.
    if (!material.hasPbrTextures()) {
      material.uvTransforms[0] = glm::mat3(1.0f);
      material.texCoords[0] = 0;
    }
    if (source.alphaMode == "MASK") material.alphaMode = AlphaMode::Mask;
    else if (source.alphaMode == "BLEND") material.alphaMode = AlphaMode::Blend;
    material.alphaCutoff = std::isfinite(source.alphaCutoff) ? static_cast<float>(source.alphaCutoff) : 0.5f;
    material.doubleSided = source.doubleSided;
    scene.materials.push_back(material);
  }
}

}  // namespace obscura::gltf
