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

Camera flythroughCamera(const Camera& start, uint32_t frame, uint32_t frameCount) {
  Camera c = start;
  const float t = frameCount > 1 ? float(frame) / float(frameCount - 1) : 0.0f;
  const glm::vec3 offset = start.position - start.target;
  // From the start, over the target at a third of the start's height, out to the far side
  // at 0.6 of the distance, swaying sideways; looking a little ahead of the target's height.
  const glm::vec3 far = start.target + glm::vec3(-0.6f * offset.x, 0.6f * offset.y, -0.6f * offset.z);
  const glm::vec3 over = start.target + glm::vec3(0.0f, offset.y / 3.0f, 0.0f);
  const glm::vec3 along = t < 0.5f ? glm::mix(start.position, over, 2.0f * t) : glm::mix(over, far, 2.0f * t - 1.0f);
  glm::vec3 side = glm::cross(offset, start.up);
  side = glm::length(side) > 0.0f ? glm::normalize(side) : glm::vec3(1.0f, 0.0f, 0.0f);
  c.position = along + side * (0.25f * glm::length(offset) * std::sin(6.28318531f * t));
  const glm::vec3 ahead = far - start.position;
  c.target = glm::vec3(c.position.x, start.target.y, c.position.z) + 0.5f * ahead;
  return c;
}

}  // namespace raybudget
