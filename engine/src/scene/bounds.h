// World-space bounds of a mesh placed by a transform (its local box's 8 corners).
#pragma once
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

}  // namespace raybudget
