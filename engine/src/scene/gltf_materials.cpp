#include "scene/gltf_materials.h"

#include <cmath>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "raybudget/error.h"
#include "scene/gltf_values.h"

namespace raybudget::gltf {
namespace {

// A material's reference to a texture: which one, which UV set, and its KHR_texture_transform.
struct TextureRef {
  int index = -1;
  int texCoord = 0;
  const tinygltf::Value* transform = nullptr;
};

template <class Info>
TextureRef textureRef(const Info& info) {
  return {info.index, info.texCoord, extension(info.extensions, "KHR_texture_transform")};
}

// A textureInfo inside a material extension's JSON (e.g. clearcoatTexture).
TextureRef textureRef(const tinygltf::Value& ext, const char* key) {
  if (!ext.Has(key) || !ext.Get(key).IsObject()) return {};
  const tinygltf::Value& info = ext.Get(key);
  TextureRef r;
  r.index = info.Has("index") && info.Get("index").IsInt() ? info.Get("index").GetNumberAsInt() : -1;
  r.texCoord = info.Has("texCoord") && info.Get("texCoord").IsInt() ? info.Get("texCoord").GetNumberAsInt() : 0;
  if (info.Has("extensions") && info.Get("extensions").Has("KHR_texture_transform")) r.transform = &info.Get("extensions").Get("KHR_texture_transform");
  return r;
}

double arrayNumber(const tinygltf::Value& v, const char* key, int i, double fallback) {
  if (!v.Has(key) || !v.Get(key).IsArray() || int(v.Get(key).ArrayLen()) <= i || !v.Get(key).Get(i).IsNumber()) return fallback;
  return v.Get(key).Get(i).GetNumberAsDouble();
}

// KHR_texture_transform's matrix: translation * rotation * scale, rotation counter-clockwise
// (the extension's GLSL, column by column).
glm::mat3 uvTransform(const tinygltf::Value& t, const std::string& where) {
  const float ox = finiteOr(arrayNumber(t, "offset", 0, 0.0), where + " offset"), oy = finiteOr(arrayNumber(t, "offset", 1, 0.0), where + " offset");
  const float sx = finiteOr(arrayNumber(t, "scale", 0, 1.0), where + " scale"), sy = finiteOr(arrayNumber(t, "scale", 1, 1.0), where + " scale");
  const float r = finiteOr(number(t, "rotation", 0.0), where + " rotation");
  const glm::mat3 translation(1, 0, 0, 0, 1, 0, ox, oy, 1);
  const glm::mat3 rotation(std::cos(r), std::sin(r), 0, -std::sin(r), std::cos(r), 0, 0, 0, 1);
  const glm::mat3 scale(sx, 0, 0, 0, sy, 0, 0, 0, 1);
  return translation * rotation * scale;
}

// The Scene::textures index a material slot samples (-1: none, or an image that could not be
// decoded). A transformed reference gets a texture of its own (shared by equal transforms).
int textureIndex(const tinygltf::Model& model, const TextureRef& ref, const std::string& where, Scene& scene) {
  if (ref.index < 0) return -1;
  if (size_t(ref.index) >= model.textures.size())
    throw Error(where + " refers to texture " + std::to_string(ref.index) + ", which does not exist");
  int texCoord = ref.texCoord;
  if (ref.transform && ref.transform->Has("texCoord") && ref.transform->Get("texCoord").IsInt()) texCoord = ref.transform->Get("texCoord").GetNumberAsInt();
  if (texCoord != 0) scene.warnings.push_back(where + ": uses TEXCOORD_" + std::to_string(texCoord) + "; TEXCOORD_0 is used");
  const int image = scene.textures[size_t(ref.index)].image;
  if (image < 0 || scene.images[size_t(image)].rgba.empty()) return -1;
  if (!ref.transform) return ref.index;
  const glm::mat3 m = uvTransform(*ref.transform, where + " KHR_texture_transform");
  if (m == glm::mat3(1.0f)) return ref.index;
  Texture t = scene.textures[size_t(ref.index)];
  t.uvTransform = m;
  for (size_t i = model.textures.size(); i < scene.textures.size(); ++i) {
    const Texture& d = scene.textures[i];
    if (d.image == t.image && d.sampler == t.sampler && d.uvTransform == m) return int(i);
  }
  scene.textures.push_back(t);
  return int(scene.textures.size() - 1);
}

// KHR_materials_clearcoat, _sheen and _specular: factors clamped to their ranges (the
// specular colour may exceed 1: it scales the IOR's F0, clamped to 1 when shading).
void loadLayers(const tinygltf::Model& model, const tinygltf::Material& gm, const std::string& at, Scene& scene, Material& m) {
  auto unit = [&](const tinygltf::Value& e, const char* key, double fallback) {
    return glm::clamp(finiteOr(number(e, key, fallback), at + " " + key), 0.0f, 1.0f);
  };
  if (const auto* e = extension(gm.extensions, "KHR_materials_clearcoat")) {
    m.clearcoat = unit(*e, "clearcoatFactor", 0.0);
    m.clearcoatRoughness = unit(*e, "clearcoatRoughnessFactor", 0.0);
    m.clearcoatTexture = textureIndex(model, textureRef(*e, "clearcoatTexture"), at + " clearcoatTexture", scene);
    m.clearcoatRoughnessTexture = textureIndex(model, textureRef(*e, "clearcoatRoughnessTexture"), at + " clearcoatRoughnessTexture", scene);
    m.clearcoatNormalTexture = textureIndex(model, textureRef(*e, "clearcoatNormalTexture"), at + " clearcoatNormalTexture", scene);
    if (e->Has("clearcoatNormalTexture")) m.clearcoatNormalScale = finiteOr(number(e->Get("clearcoatNormalTexture"), "scale", 1.0), at + " clearcoatNormalTexture.scale");
  }
  if (const auto* e = extension(gm.extensions, "KHR_materials_sheen")) {
    for (int k = 0; k < 3; ++k) m.sheenColor[k] = glm::clamp(finiteOr(arrayNumber(*e, "sheenColorFactor", k, 0.0), at + " sheenColorFactor"), 0.0f, 1.0f);
    m.sheenRoughness = unit(*e, "sheenRoughnessFactor", 0.0);
    m.sheenColorTexture = textureIndex(model, textureRef(*e, "sheenColorTexture"), at + " sheenColorTexture", scene);
    m.sheenRoughnessTexture = textureIndex(model, textureRef(*e, "sheenRoughnessTexture"), at + " sheenRoughnessTexture", scene);
  }
  if (const auto* e = extension(gm.extensions, "KHR_materials_specular")) {
    m.specular = unit(*e, "specularFactor", 1.0);
    for (int k = 0; k < 3; ++k)
      m.specularColor[k] = glm::clamp(finiteOr(arrayNumber(*e, "specularColorFactor", k, 1.0), at + " specularColorFactor"), 0.0f, 1.0e4f);
    m.specularTexture = textureIndex(model, textureRef(*e, "specularTexture"), at + " specularTexture", scene);
    m.specularColorTexture = textureIndex(model, textureRef(*e, "specularColorTexture"), at + " specularColorTexture", scene);
  }
}

}  // namespace

void loadImagesAndTextures(const tinygltf::Model& model, const std::string& file, Scene& scene) {
  for (size_t i = 0; i < model.images.size(); ++i) {
    const tinygltf::Image& gi = model.images[i];
    Image img;
    img.name = gi.name.empty() ? gi.uri : gi.name;
    const size_t texels = size_t(std::max(gi.width, 0)) * size_t(std::max(gi.height, 0));
    const size_t channelBytes = gi.bits == 16 ? 2 : 1;
    if (texels == 0 || gi.component < 1 || gi.component > 4 || gi.image.size() < texels * size_t(gi.component) * channelBytes) {
      scene.warnings.push_back(file + ": image " + std::to_string(i) + " ('" + img.name + "') could not be decoded; textures using it are ignored");
      scene.images.push_back(std::move(img));
      continue;
    }
    img.width = uint32_t(gi.width);
    img.height = uint32_t(gi.height);
    img.rgba.resize(texels * 4);
    for (size_t t = 0; t < texels; ++t) {
      uint8_t c[4] = {0, 0, 0, 255};
      for (int k = 0; k < gi.component; ++k) {
        const size_t at = (t * size_t(gi.component) + size_t(k)) * channelBytes;
        c[k] = channelBytes == 2 ? gi.image[at + 1] : gi.image[at];  // little-endian: high byte
      }
      if (gi.component <= 2) {  // grey (+alpha)
        const uint8_t a = gi.component == 2 ? c[1] : 255;
        c[1] = c[2] = c[0];
        c[3] = a;
      }
      std::copy(c, c + 4, img.rgba.begin() + std::ptrdiff_t(t * 4));
    }
    scene.images.push_back(std::move(img));
  }
  for (const tinygltf::Sampler& gs : model.samplers) {
    Sampler s;
    s.magLinear = gs.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST;
    s.minLinear = gs.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST && gs.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST &&
                  gs.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
    s.mipLinear = gs.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST &&
                  gs.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST;
    s.wrapS = gs.wrapS;
    s.wrapT = gs.wrapT;
    scene.samplers.push_back(s);
  }
  for (size_t i = 0; i < model.textures.size(); ++i) {
    const tinygltf::Texture& gt = model.textures[i];
    const std::string at = file + ": texture " + std::to_string(i);
    if (gt.source >= int(model.images.size())) throw Error(at + " refers to image " + std::to_string(gt.source) + ", which does not exist");
    if (gt.sampler >= int(model.samplers.size())) throw Error(at + " refers to sampler " + std::to_string(gt.sampler) + ", which does not exist");
    scene.textures.push_back(Texture{gt.source, gt.sampler});
  }
}

void loadMaterials(const tinygltf::Model& model, const std::string& file, Scene& scene) {
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& gm = model.materials[i];
    const std::string at = file + ": material " + std::to_string(i) + " ('" + gm.name + "')";
    const auto& pbr = gm.pbrMetallicRoughness;
    Material m;
    m.name = gm.name;
    for (int k = 0; k < 4 && k < int(pbr.baseColorFactor.size()); ++k)
      m.baseColorFactor[k] = glm::clamp(finiteOr(pbr.baseColorFactor[size_t(k)], at + " baseColorFactor"), 0.0f, 1.0f);
    m.metallic = glm::clamp(finiteOr(pbr.metallicFactor, at + " metallicFactor"), 0.0f, 1.0f);
    m.roughness = glm::clamp(finiteOr(pbr.roughnessFactor, at + " roughnessFactor"), 0.0f, 1.0f);
    for (int k = 0; k < 3 && k < int(gm.emissiveFactor.size()); ++k)
      m.emissive[k] = std::max(finiteOr(gm.emissiveFactor[size_t(k)], at + " emissiveFactor"), 0.0f);
    m.alphaMode = gm.alphaMode == "MASK" ? AlphaMode::Mask : gm.alphaMode == "BLEND" ? AlphaMode::Blend : AlphaMode::Opaque;
    m.alphaCutoff = finiteOr(gm.alphaCutoff, at + " alphaCutoff");
    m.doubleSided = gm.doubleSided;
    m.normalScale = finiteOr(gm.normalTexture.scale, at + " normalTexture.scale");
    m.baseColorTexture = textureIndex(model, textureRef(pbr.baseColorTexture), at, scene);
    m.metallicRoughnessTexture = textureIndex(model, textureRef(pbr.metallicRoughnessTexture), at, scene);
    m.normalTexture = textureIndex(model, textureRef(gm.normalTexture), at, scene);
    m.emissiveTexture = textureIndex(model, textureRef(gm.emissiveTexture), at, scene);
    if (const auto* e = extension(gm.extensions, "KHR_materials_emissive_strength"))
      m.emissive *= std::max(finiteOr(number(*e, "emissiveStrength", 1.0), at + " emissiveStrength"), 0.0f);
    if (const auto* e = extension(gm.extensions, "KHR_materials_transmission"))
      m.transmission = glm::clamp(finiteOr(number(*e, "transmissionFactor", 0.0), at + " transmissionFactor"), 0.0f, 1.0f);
    if (const auto* e = extension(gm.extensions, "KHR_materials_ior")) {
      m.ior = finiteOr(number(*e, "ior", 1.5), at + " ior");
      if (m.ior < 1.0f) m.ior = 1.0f;  // glTF allows 0 as "no refraction": same as 1 here
    }
    if (const auto* e = extension(gm.extensions, "KHR_materials_volume")) {
      m.thickness = std::max(finiteOr(number(*e, "thicknessFactor", 0.0), at + " thicknessFactor"), 0.0f);
      const double dist = number(*e, "attenuationDistance", 0.0);
      m.attenuationDistance = std::isfinite(dist) && dist > 0.0 ? float(dist) : 0.0f;
      if (e->Has("attenuationColor") && e->Get("attenuationColor").IsArray())
        for (int k = 0; k < 3 && k < int(e->Get("attenuationColor").ArrayLen()); ++k)
          m.attenuationColor[k] = glm::clamp(finiteOr(e->Get("attenuationColor").Get(k).GetNumberAsDouble(), at + " attenuationColor"), 0.0f, 1.0f);
    }
    m.unlit = extension(gm.extensions, "KHR_materials_unlit") != nullptr;
    loadLayers(model, gm, at, scene, m);
    scene.materials.push_back(m);
  }
}

}  // namespace raybudget::gltf
