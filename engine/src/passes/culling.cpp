#include "passes/frame_context.h"

namespace raybudget::passes {

bool sphereInFrustum(const glm::mat4& m, const glm::vec4& sphere) {
  const glm::vec4 r0(m[0][0], m[1][0], m[2][0], m[3][0]);
  const glm::vec4 r1(m[0][1], m[1][1], m[2][1], m[3][1]);
  const glm::vec4 r2(m[0][2], m[1][2], m[2][2], m[3][2]);
  const glm::vec4 r3(m[0][3], m[1][3], m[2][3], m[3][3]);
  const glm::vec4 planes[6] = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2};
  for (const glm::vec4& p : planes) {
    const float len = glm::length(glm::vec3(p));
    if (len == 0.0f) continue;
    if ((glm::dot(glm::vec3(p), glm::vec3(sphere)) + p.w) / len < -sphere.w) return false;
  }
  return true;
}

}  // namespace raybudget::passes
