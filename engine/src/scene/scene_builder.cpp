#include "raybudget/scene_builder.h"

#include <cmath>
#include <cstring>

#include "raybudget/error.h"
#include "scene/bounds.h"
#include "scene/triangles.h"

namespace raybudget {
namespace {

glm::vec3 read(const Float3Stream& s, size_t i) {
  glm::vec3 v;
  std::memcpy(&v, static_cast<const std::byte*>(s.data) + i * (s.stride ? s.stride : sizeof(glm::vec3)), sizeof(v));
  return v;
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void within(float v, float lo, float hi, const std::string& what) {
  if (!(v >= lo && v <= hi)) throw Error(what + " is " + std::to_string(v) + ", outside " + std::to_string(lo) + ".." + std::to_string(hi));
}

}  // namespace

uint32_t SceneBuilder::addMesh(const MeshInput& in) {
  const std::string at = "mesh " + std::to_string(scene_.meshes.size()) + " ('" + in.name + "')";
  if (!in.positions.data || in.vertexCount == 0) throw Error(at + ": no positions");
  if (in.indices.size() % 3 != 0) throw Error(at + ": " + std::to_string(in.indices.size()) + " indices are not a triangle list");
  std::vector<glm::vec3> positions(in.vertexCount);
  for (size_t i = 0; i < in.vertexCount; ++i) {
    positions[i] = read(in.positions, i);
    if (!finite(positions[i])) throw Error(at + ": the position of vertex " + std::to_string(i) + " is not finite (NaN or Inf)");
  }
  for (size_t i = 0; i < in.indices.size(); ++i)
    if (in.indices[i] >= in.vertexCount)
      throw Error(at + ": index " + std::to_string(i) + " is " + std::to_string(in.indices[i]) + ", out of range for " +
                  std::to_string(in.vertexCount) + " vertices");
  size_t dropped = 0;
  const std::vector<uint32_t> kept = dropZeroAreaTriangles(positions, in.indices, dropped);
  if (dropped) {
    scene_.stats.droppedDegenerateTriangles += dropped;
    scene_.warnings.push_back(at + ": dropped " + std::to_string(dropped) + " zero-area triangles");
  }
  if (kept.empty()) throw Error(at + ": no triangle with any area");
  const std::vector<glm::vec3> generated = in.normals.data ? std::vector<glm::vec3>{} : areaWeightedNormals(positions, kept);
  Mesh mesh;
  mesh.name = in.name.empty() ? "mesh" + std::to_string(scene_.meshes.size()) : in.name;
  mesh.vertices.resize(in.vertexCount);
  for (size_t i = 0; i < in.vertexCount; ++i) {
    Vertex& v = mesh.vertices[i];
    v.position = positions[i];
    const glm::vec3 n = in.normals.data ? read(in.normals, i) : generated[i];
    if (!finite(n)) throw Error(at + ": the normal of vertex " + std::to_string(i) + " is not finite");
    // Unit normals are kept as given (normalising again would move them by an ulp).
    const float length = glm::length(n);
    v.normal = std::fabs(length - 1.0f) <= 1e-6f ? n : length > 0.0f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  mesh.indices = kept;
  mesh.primitives.push_back({0, uint32_t(kept.size()), -1});  // the instance's material, set at addInstance
  mesh.boundsMin = mesh.boundsMax = positions[kept[0]];
  for (uint32_t i : kept) {
    mesh.boundsMin = glm::min(mesh.boundsMin, positions[i]);
    mesh.boundsMax = glm::max(mesh.boundsMax, positions[i]);
  }
  scene_.meshes.push_back(std::move(mesh));
  return uint32_t(scene_.meshes.size() - 1);
}

uint32_t SceneBuilder::addMaterial(const MaterialHints& h) {
  const std::string at = "material " + std::to_string(scene_.materials.size()) + " ('" + h.name + "')";
  for (int c = 0; c < 4; ++c) within(h.baseColor[c], 0.0f, 1.0f, at + ": base colour channel " + std::to_string(c));
  within(h.metallic, 0.0f, 1.0f, at + ": metallic");
  within(h.roughness, 0.0f, 1.0f, at + ": roughness");
  within(h.transmission, 0.0f, 1.0f, at + ": transmission");
  within(h.ior, 1.0f, 3.0f, at + ": IOR");
  within(h.thickness, 0.0f, 1e6f, at + ": thickness");
  within(h.attenuationDistance, 0.0f, 1e9f, at + ": attenuation distance");
  for (int c = 0; c < 3; ++c) within(h.attenuationColor[c], 0.0f, 1.0f, at + ": attenuation colour channel " + std::to_string(c));
  for (int c = 0; c < 3; ++c) within(h.emissive[c], 0.0f, 1e6f, at + ": emissive channel " + std::to_string(c));
  Material m;
  m.name = h.name;
  m.baseColorFactor = h.baseColor;
  m.metallic = h.metallic;
  m.roughness = h.roughness;
  m.transmission = h.transmission;
  m.ior = h.ior;
  m.thickness = h.thickness;
  m.attenuationDistance = h.attenuationDistance;
  m.attenuationColor = h.attenuationColor;
  m.emissive = h.emissive;
  m.unlit = h.unlit;
  m.doubleSided = h.doubleSided;
  scene_.materials.push_back(m);
  return uint32_t(scene_.materials.size() - 1);
}

uint32_t SceneBuilder::addInstance(uint32_t mesh, uint32_t material, const glm::mat4& transform, const RayBudgetParams& params, std::string name) {
  const uint32_t id = uint32_t(scene_.objects.size());
  const std::string at = "instance " + std::to_string(id) + " ('" + name + "')";
  if (mesh >= scene_.meshes.size()) throw Error(at + ": mesh " + std::to_string(mesh) + " does not exist");
  if (material >= scene_.materials.size()) throw Error(at + ": material " + std::to_string(material) + " does not exist");
  validateRayBudgetParams(params, at);
  validateTransform(transform, at);
  // Each instance draws its mesh with its own material: a mesh used with another material
  // than its first instance's gets one copy per such material (the renderer keeps materials
  // per primitive; the BVH build shares the copies' structure).
  uint32_t meshIndex = mesh;
  Mesh& m = scene_.meshes[mesh];
  if (m.primitives[0].material < 0) {
    m.primitives[0].material = int(material);
  } else if (m.primitives[0].material != int(material)) {
    const auto [variant, added] = materialVariants_.try_emplace({mesh, material}, 0u);
    if (added) {
      Mesh copy = m;
      copy.primitives[0].material = int(material);
      scene_.meshes.push_back(std::move(copy));
      variant->second = uint32_t(scene_.meshes.size() - 1);
    }
    meshIndex = variant->second;
  }
  Object o;
  o.id = id;
  o.name = name.empty() ? "instance" + std::to_string(id) : std::move(name);
  o.mesh = meshIndex;
  o.transform = transform;
  o.params = params;
  worldBounds(scene_.meshes[meshIndex], transform, o.boundsMin, o.boundsMax);
  scene_.objects.push_back(std::move(o));
  scene_.stats.triangles += scene_.meshes[meshIndex].indices.size() / 3;
  return id;
}

void SceneBuilder::addLight(const Light& light) {
  const std::string at = "light " + std::to_string(scene_.lights.size()) + " ('" + light.name + "')";
  if (!finite(light.color) || !finite(light.position) || !finite(light.direction) || !std::isfinite(light.intensity) || light.intensity < 0.0f ||
      !std::isfinite(light.range) || light.range < 0.0f)
    throw Error(at + ": a value is negative or not finite");
  if (light.type != LightType::Point && glm::length(light.direction) == 0.0f) throw Error(at + ": no direction");
  Light l = light;
  if (l.type != LightType::Point && std::fabs(glm::length(l.direction) - 1.0f) > 1e-6f) l.direction = glm::normalize(l.direction);
  scene_.lights.push_back(l);
}

void SceneBuilder::setCamera(const Camera& camera) { scene_.camera = camera; }

Scene SceneBuilder::build() const {
  if (scene_.objects.empty()) throw Error("SceneBuilder: no instance was added");
  Scene s = scene_;
  s.path = "host-scene";
  finishScene(s);
  return s;
}

}  // namespace raybudget
