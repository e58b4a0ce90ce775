#include "raybudget/camera.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace raybudget {

glm::mat4 Camera::view() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::projection(float aspect) const {
  // glm's right-handed, zero-to-one perspective; flip y for Vulkan's clip space.
  glm::mat4 p = glm::perspectiveRH_ZO(yfov, aspect, znear, zfar);
  p[1][1] *= -1.0f;
  return p;
}

Camera orbitCamera(const Camera& start, uint32_t frame, uint32_t frameCount) {
  Camera c = start;
  const glm::vec3 offset = start.position - start.target;
  const float radius = std::sqrt(offset.x * offset.x + offset.z * offset.z);
  const float phase = std::atan2(offset.z, offset.x);
  const float turn = frameCount > 0 ? 6.28318531f * float(frame) / float(frameCount) : 0.0f;
  c.position = start.target + glm::vec3(radius * std::cos(phase + turn), offset.y, radius * std::sin(phase + turn));
  return c;
}

}  // namespace raybudget
