// The scene raybudget renders: meshes, materials, objects (node instances), lights and a
// camera, as loaded from glTF 2.0 and validated. Plain C++: no Vulkan here.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "raybudget/camera.h"

namespace raybudget {

struct Vertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec2 uv{0.0f};
  glm::vec4 color{1.0f};
};

// A glTF primitive after conversion to a triangle list: a range of its mesh's indices.
struct Primitive {
  uint32_t firstIndex = 0;
  uint32_t indexCount = 0;
  int32_t material = -1;  // -1: the glTF default material
};

struct Mesh {
  std::string name;
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangle list
  std::vector<Primitive> primitives;
  glm::vec3 boundsMin{0.0f};
  glm::vec3 boundsMax{0.0f};
};

// Decoded texture image, always RGBA8.
struct Image {
  std::string name;
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> rgba;
};

struct Sampler {
  bool magLinear = true;
  bool minLinear = true;
  bool mipLinear = true;
  int wrapS = 10497;  // glTF codes: 10497 REPEAT, 33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT
  int wrapT = 10497;
};

struct Texture {
  int image = -1;
  int sampler = -1;  // -1: the default sampler
  // KHR_texture_transform (translation * rotation * scale, applied to (u, v, 1)): a texture
  // reference with a transform becomes a texture of its own after the glTF file's textures.
  glm::mat3 uvTransform{1.0f};
};

enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;
  glm::vec3 emissive{0.0f};  // emissiveFactor * KHR_materials_emissive_strength
  float normalScale = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
  bool unlit = false;
  float transmission = 0.0f;  // KHR_materials_transmission
  float ior = 1.5f;           // KHR_materials_ior
  float thickness = 0.0f;     // KHR_materials_volume
  float attenuationDistance = 0.0f;  // 0: infinite
  glm::vec3 attenuationColor{1.0f};
  int baseColorTexture = -1;  // indices into Scene::textures
  int metallicRoughnessTexture = -1;
  int normalTexture = -1;
  int emissiveTexture = -1;
  // KHR_materials_clearcoat: a dielectric coat (IOR 1.5) over the base.
  float clearcoat = 0.0f;
  float clearcoatRoughness = 0.0f;
  float clearcoatNormalScale = 1.0f;
  int clearcoatTexture = -1;           // R
  int clearcoatRoughnessTexture = -1;  // G
  int clearcoatNormalTexture = -1;
  // KHR_materials_sheen: a retro-reflective fabric layer (Charlie distribution).
  glm::vec3 sheenColor{0.0f};
  float sheenRoughness = 0.0f;
  int sheenColorTexture = -1;      // RGB
  int sheenRoughnessTexture = -1;  // A
  // KHR_materials_specular: the dielectric reflection's strength and its F0 colour.
  float specular = 1.0f;
  glm::vec3 specularColor{1.0f};
  int specularTexture = -1;       // A
  int specularColorTexture = -1;  // RGB
};

// Per-object heuristic inputs (the paper's K, Q, I), from glTF node extras.raybudget.
// Absent values are filled from defaults by the heuristic (later issue).
struct RayBudgetParams {
  std::optional<float> importanceK;
  std::optional<float> raysQ;
  std::optional<float> hysteresisI;
};

// One object = one node instance of one mesh; `id` is its stable index in Scene::objects.
struct Object {
  uint32_t id = 0;
  std::string name;
  uint32_t mesh = 0;
  int gltfNode = -1;
  glm::mat4 transform{1.0f};
  glm::vec3 boundsMin{0.0f};  // world space
  glm::vec3 boundsMax{0.0f};
  RayBudgetParams params;
};

enum class LightType { Directional, Point, Spot };

struct Light {
  std::string name;
  LightType type = LightType::Directional;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;  // lux (directional) or candela (point, spot), as glTF defines
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // direction the light travels
  float range = 0.0f;                      // 0: infinite
  float innerConeAngle = 0.0f;
  float outerConeAngle = 0.7853982f;
};

// A reflection probe: a cube map of the scene captured from `center`, which the raster
// fallback reflects for the points inside its box, with parallax correction against the
// box's walls. Authored on a glTF node as extras.raybudget.reflectionProbe = true: the
// node's world transform maps the cube [-1, 1]^3 to the box (its translation is the centre).
inline constexpr size_t kMaxReflectionProbes = 8;
struct ReflectionProbe {
  std::string name;
  glm::vec3 center{0.0f};
  glm::vec3 boxMin{0.0f};
  glm::vec3 boxMax{0.0f};
};

struct SceneStats {
  size_t droppedDegenerateTriangles = 0;
  size_t skippedPointLinePrimitives = 0;
  size_t triangles = 0;  // drawn, over all objects
};

struct Scene {
  std::filesystem::path path;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Image> images;
  std::vector<Sampler> samplers;
  std::vector<Texture> textures;
  std::vector<Object> objects;
  std::vector<Light> lights;
  std::vector<ReflectionProbe> reflectionProbes;  // authored, at most kMaxReflectionProbes
  std::optional<Camera> camera;  // the glTF camera, when the scene has one
  bool usesDefaultSun = false;   // no KHR_lights_punctual light: the default sun was added
  glm::vec3 boundsMin{0.0f};
  glm::vec3 boundsMax{0.0f};
  SceneStats stats;
  std::vector<std::string> warnings;
};

// The sun a scene without lights gets: white, 3 lux, from above and slightly behind the
// default camera (direction of travel normalize(-0.3, -1, -0.4)).
Light defaultSun();

// A generated stress scene: a square grid of `count` cubes (0.8 units, one mesh instanced)
// on the ground, lit by the default sun (selection benchmarks and tests).
Scene cubeGridScene(uint32_t count);

// How loadScene treats what it can repair (docs/ROBUSTNESS.md): by default it repairs and
// says so in Scene::warnings; `strict` refuses instead, with the first repair as the error.
struct LoadOptions {
  bool strict = false;
};

// Loads and validates a .gltf or .glb file. Throws raybudget::Error naming the file and the
// problem on malformed input; recoverable oddities (points/lines, zero-area triangles, NaN
// or zero normals, images that cannot be read) are repaired and become warnings in
// Scene::warnings (with LoadOptions::strict, errors).
Scene loadScene(const std::filesystem::path& path, const LoadOptions& options = {});

// The render space's origin in world space: the centre of the scene's bounds where that lies
// more than kRebaseDistance from the world's origin, else the world's origin. The frame works
// in float in render space (world minus the origin), so that a scene far from the world's
// origin keeps the precision it has near it (docs/ROBUSTNESS.md).
inline constexpr float kRebaseDistance = 1000.0f;
glm::vec3 renderOrigin(const Scene& scene);
// `scene` in render space: objects (and their bounds), lights and the camera moved by -origin.
Scene inRenderSpace(const Scene& scene, const glm::vec3& origin);
// A world-space camera, and an object's world transform, in render space (the transform's
// translation alone moves: near the origin it subtracts exactly, Sterbenz).
Camera inRenderSpace(const Camera& camera, const glm::vec3& origin);
glm::mat4 inRenderSpace(const glm::mat4& transform, const glm::vec3& origin);

// The probes the fallback reflects: the authored ones, else one at the centre of the
// scene's bounds with the bounds as its box where the scene has surroundings: at least two
// objects, one spanning 90% of the bounds along two axes (a floor, a wall), and the centre
// inside no model's bounding box (one covering under 90% of the scene's). Otherwise none:
// the sky stands in.
std::vector<ReflectionProbe> reflectionProbesOf(const Scene& scene);

// The camera to render with: the scene's own, else one framing its bounds.
Camera defaultCamera(const Scene& scene, float aspect);

// Where the camera paths (orbit, fly-through) start: the default camera's position pulled
// 40% towards the centre of the scene's bounds, looking at that centre with world up (a
// glTF camera's own target is just a point ahead of it, and an orbit around it would
// leave an enclosed scene).
Camera pathStartCamera(const Scene& scene, float aspect);

// The fly-through's shape for `scene` from `start` (pathStartCamera): where the path's middle,
// a third of the start's height over the target, lies inside an object's bounds with some of
// its triangles straight above (inside a model: flown through, a single model showed its
// inside in a third of the frames and empty ground ahead in another), the path clears the
// highest such object by 5% of the scene's radius and looks at the target throughout;
// elsewhere (a level's open centre, between walls) the plain fly-through.
FlythroughShape flythroughShape(const Scene& scene, const Camera& start);

// The ray-traced effects a scene can show at all: shadows when it has a light; reflections
// when some object's material can be smooth enough (roughness at most maxRoughness, the
// least value of its roughness texture counted); refractions when one is transmissive.
// Unlit materials show none. The renderer builds no pipeline and runs no pass for the others.
struct SceneEffects {
  bool shadows = false, reflections = false, refractions = false;
};
SceneEffects sceneEffects(const Scene& scene, float maxRoughness);

// Writes `params` of each object back into the glTF file as node extras.raybudget,
// keeping everything else as loaded. Used by the editor and the round-trip test.
void saveRayBudgetParams(const std::filesystem::path& source, const std::filesystem::path& destination,
                         const std::vector<std::pair<int, RayBudgetParams>>& nodeParams);

// Throws Error naming `where` on a non-finite, singular (zero-scale) or absurd (a component
// beyond 1e7) transform.
void validateTransform(const glm::mat4& transform, const std::string& where);

// Moves object `id` to `transform` and updates its world bounds (and the scene's). Throws
// Error for an unknown object or a non-finite, singular or absurd transform.
void setObjectTransform(Scene& scene, uint32_t id, const glm::mat4& transform);

// Validates K/Q/I: finite, non-negative, and below kMaxParamValue. Throws Error naming `where`.
inline constexpr float kMaxParamValue = 1.0e6f;
void validateRayBudgetParams(const RayBudgetParams& params, const std::string& where);

}  // namespace raybudget
