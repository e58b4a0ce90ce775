// A scene from a host engine's own arrays instead of a glTF file: meshes from positions
// (and normals) at any stride with a triangle list, materials from a few hints, instances
// with a transform and K/Q/I, lights and a camera. Everything is copied and validated, so the
// arrays need live only during the call; an error names the mesh or instance and what is
// wrong. build() gives the raybudget::Scene that core::Context and Renderer take; object
// IDs are the instances' order (what the host writes into its G-buffer's object IDs),
// material IDs the materials' order.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "raybudget/scene.h"

namespace raybudget {

// `count` elements of three floats each, `stride` bytes apart (0: tightly packed), e.g. one
// attribute of a host's interleaved vertex array.
struct Float3Stream {
  const void* data = nullptr;
  size_t stride = 0;
};

struct MeshInput {
  std::string name;
  size_t vertexCount = 0;
  Float3Stream positions;
  Float3Stream normals;             // absent (data null): area-weighted normals
  std::span<const uint32_t> indices;  // a triangle list into the vertices
};

// What the renderer needs of a surface (glTF's metallic-roughness model).
struct MaterialHints {
  std::string name;
  glm::vec4 baseColor{1.0f};     // linear RGB, alpha
  float metallic = 0.0f;         // 0..1
  float roughness = 0.5f;        // 0..1
  float transmission = 0.0f;     // 0..1: glass
  float ior = 1.5f;              // 1..3
  float thickness = 0.0f;        // > 0: a volume (refracts in and out), else a thin wall
  float attenuationDistance = 0.0f;  // a volume's Beer-Lambert distance (0: no absorption)
  glm::vec3 attenuationColor{1.0f};  // the colour left after attenuationDistance
  glm::vec3 emissive{0.0f};
  bool unlit = false;
  bool doubleSided = false;
};

class SceneBuilder {
 public:
  // Returns the mesh's index. Throws Error naming the mesh on a non-finite position or
  // normal, an index out of range, an index count not a multiple of 3, or no triangle with
  // area (zero-area triangles are dropped and counted in the scene's warnings).
  uint32_t addMesh(const MeshInput& mesh);
  // Returns the material's index. Throws Error naming it on a value out of range.
  uint32_t addMaterial(const MaterialHints& material);
  // Returns the object ID. Throws Error on an unknown mesh or material, a non-finite,
  // singular or absurd transform, or bad K/Q/I.
  uint32_t addInstance(uint32_t mesh, uint32_t material, const glm::mat4& transform, const RayBudgetParams& params = {},
                       std::string name = {});
  void addLight(const Light& light);  // throws Error on non-finite values
  void setCamera(const Camera& camera);
  // The scene: bounds, the default sun when no light was added. Throws Error without instances.
  Scene build() const;

 private:
  Scene scene_;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> materialVariants_;  // (mesh, material) -> its copy
};

}  // namespace raybudget
