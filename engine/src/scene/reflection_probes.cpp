// Where the reflection probe goes when a scene authors none: at the centre of its bounds,
// with the bounds as its box, where the scene has surroundings to capture. A probe stands for
// what encloses the objects (a floor, walls, a building): a scene of one model, or of objects
// with nothing spanning them (spheres in a grid), reflects the sky better than a probe
// amid the objects, and a centre inside a model's bounding box (a car, the cloth under it)
// would show the model's insides.
#include "raybudget/scene.h"

namespace raybudget {
namespace {

constexpr float kSpan = 0.9f;  // what share of the scene's extent "spanning" takes

}  // namespace

std::vector<ReflectionProbe> reflectionProbesOf(const Scene& scene) {
  if (!scene.reflectionProbes.empty()) return scene.reflectionProbes;
  const glm::vec3 center = 0.5f * (scene.boundsMin + scene.boundsMax), extent = scene.boundsMax - scene.boundsMin;
  const float volume = extent.x * extent.y * extent.z;
  bool enclosed = false;  // an object spans the scene along two axes at least (a floor, a wall)
  for (const Object& o : scene.objects) {
    const glm::vec3 e = o.boundsMax - o.boundsMin;
    enclosed = enclosed || int(e.x >= kSpan * extent.x) + int(e.y >= kSpan * extent.y) + int(e.z >= kSpan * extent.z) >= 2;
    const bool surroundings = e.x * e.y * e.z >= kSpan * volume;  // a building in one mesh, not a model
    if (!surroundings && glm::all(glm::greaterThan(center, o.boundsMin)) && glm::all(glm::lessThan(center, o.boundsMax))) return {};
  }
  if (!enclosed || scene.objects.size() < 2) return {};
  // The bounds, grown a little so that the surfaces on them lie inside the box.
  const glm::vec3 pad = 1e-3f * extent + 1e-4f;
  ReflectionProbe p;
  p.name = "scene bounds";
  p.center = center;
  p.boxMin = scene.boundsMin - pad;
  p.boxMax = scene.boundsMax + pad;
  return {p};
}

}  // namespace raybudget
