#include <algorithm>
#include <set>

#include "raybudget/scene.h"

namespace raybudget {
namespace {

// The least roughness a material's pixels can have: its factor times the least green value
// of its metallic-roughness texture (glTF: roughness in G), 1 without one.
float leastRoughness(const Scene& scene, const Material& m) {
  float least = 1.0f;
  if (m.metallicRoughnessTexture >= 0 && size_t(m.metallicRoughnessTexture) < scene.textures.size()) {
    const int image = scene.textures[size_t(m.metallicRoughnessTexture)].image;
    if (image >= 0 && size_t(image) < scene.images.size()) {
      const std::vector<uint8_t>& rgba = scene.images[size_t(image)].rgba;
      uint8_t g = 255;
      for (size_t i = 1; i < rgba.size(); i += 4) g = std::min(g, rgba[i]);
      least = g / 255.0f;
    } else {
      least = 0.0f;  // unknown image: assume it may be smooth anywhere
    }
  }
  return m.roughness * least;
}

}  // namespace

SceneEffects sceneEffects(const Scene& scene, float maxRoughness) {
  SceneEffects e;
  e.shadows = !scene.lights.empty();
  std::set<int> used;
  for (const Object& o : scene.objects)
    for (const Primitive& p : scene.meshes.at(o.mesh).primitives) used.insert(p.material);
  for (int id : used) {
    const Material m = id >= 0 && size_t(id) < scene.materials.size() ? scene.materials[size_t(id)] : Material{};  // -1: glTF's default
    if (m.unlit) continue;  // shows its colour only: traces nothing
    e.reflections = e.reflections || leastRoughness(scene, m) <= maxRoughness;
    e.refractions = e.refractions || m.transmission > 0.0f;
  }
  return e;
}

}  // namespace raybudget
