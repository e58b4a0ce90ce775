// World-space bounds: of a mesh placed by a transform (its local box's 8 corners), and of a scene.
#pragma once
#include <cmath>
#include <limits>

#include "raybudget/scene.h"

namespace raybudget {

inline void worldBounds(const Mesh& mesh, const glm::mat4& transform, glm::vec3& lo, glm::vec3& hi) {
  lo = glm::vec3(std::numeric_limits<float>::max());
  hi = glm::vec3(-std::numeric_limits<float>::max());
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? mesh.boundsMax.x : mesh.boundsMin.x, (c & 2) ? mesh.boundsMax.y : mesh.boundsMin.y,
                           (c & 4) ? mesh.boundsMax.z : mesh.boundsMin.z);
    const glm::vec3 w = glm::vec3(transform * glm::vec4(corner, 1.0f));
    lo = glm::min(lo, w);
    hi = glm::max(hi, w);
  }
}

// Whether a box is finite: a transform that overflows float range leaves infinities (or NaN).
inline bool finiteBounds(const glm::vec3& lo, const glm::vec3& hi) {
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(lo[c]) || !std::isfinite(hi[c])) return false;
  return true;
}

// The scene's bounds: the union of its objects' (it has at least one).
inline void updateSceneBounds(Scene& scene) {
  scene.boundsMin = scene.objects[0].boundsMin;
  scene.boundsMax = scene.objects[0].boundsMax;
  for (const Object& o : scene.objects) {
    scene.boundsMin = glm::min(scene.boundsMin, o.boundsMin);
    scene.boundsMax = glm::max(scene.boundsMax, o.boundsMax);
  }
}

// What every finished scene has: its bounds, and the default sun when it has no light.
inline void finishScene(Scene& scene) {
  updateSceneBounds(scene);
  if (scene.lights.empty()) {
    scene.lights.push_back(defaultSun());
    scene.usesDefaultSun = true;
  }
}

}  // namespace raybudget
