#include "camera_control.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace raybudget::editor {
namespace {

constexpr float kPoleMargin = 0.01745f;  // 1 degree

// `offset` turned by yaw about `up` and by pitch towards `up`, its length kept.
glm::vec3 turn(glm::vec3 offset, glm::vec3 up, float yaw, float pitch) {
  up = glm::normalize(up);
  const float length = glm::length(offset);
  if (length <= 0.0f) return offset;
  glm::vec3 dir = offset / length;
  const float elevation = std::asin(std::clamp(glm::dot(dir, up), -1.0f, 1.0f));
  const float newElevation = std::clamp(elevation + pitch, -1.5707963f + kPoleMargin, 1.5707963f - kPoleMargin);
  glm::vec3 flat = dir - up * glm::dot(dir, up);
  if (glm::length(flat) < 1e-6f) flat = glm::abs(up.x) < 0.9f ? glm::cross(up, glm::vec3(1, 0, 0)) : glm::cross(up, glm::vec3(0, 0, 1));
  flat = glm::normalize(glm::vec3(glm::rotate(glm::mat4(1.0f), yaw, up) * glm::vec4(glm::normalize(flat), 0.0f)));
  return length * (flat * std::cos(newElevation) + up * std::sin(newElevation));
}

}  // namespace

Camera orbit(const Camera& camera, float yaw, float pitch) {
  Camera c = camera;
  c.position = c.target + turn(camera.position - camera.target, camera.up, yaw, pitch);
  return c;
}

Camera dolly(const Camera& camera, float factor) {
  Camera c = camera;
  c.position = c.target + (camera.position - camera.target) * std::max(0.01f, 1.0f - factor);
  return c;
}

Camera fly(const Camera& camera, float forward, float right, float up) {
  const glm::vec3 f = glm::normalize(camera.target - camera.position);
  const glm::vec3 r = glm::normalize(glm::cross(f, camera.up));
  const glm::vec3 u = glm::cross(r, f);
  Camera c = camera;
  const glm::vec3 step = f * forward + r * right + u * up;
  c.position += step;
  c.target += step;
  return c;
}

Camera look(const Camera& camera, float yaw, float pitch) {
  Camera c = camera;
  // The view direction is the negated offset of an orbit of the position around the target.
  c.target = c.position - turn(camera.position - camera.target, camera.up, yaw, -pitch);
  return c;
}

}  // namespace raybudget::editor
