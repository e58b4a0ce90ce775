#include "raybudget/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "raybudget/error.h"

namespace raybudget {

glm::mat4 Camera::view() const {
  const glm::vec3 forward = glm::normalize(target - position);
  glm::vec3 u = up;  // as given otherwise: the same matrix as glm::lookAt's, bit for bit
  if (std::fabs(glm::dot(forward, glm::normalize(up))) > 0.9999f)  // parallel: lookAt's cross product vanishes
    u = std::fabs(forward.z) < 0.9f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  return glm::lookAt(position, target, u);
}

void validateCamera(const Camera& c, const std::string& where) {
  auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(c.position) || !finite(c.target) || !finite(c.up) || !std::isfinite(c.yfov) || !std::isfinite(c.znear) || !std::isfinite(c.zfar))
    throw Error(where + ": the camera has a non-finite value");
  const glm::vec3 d = c.target - c.position;
  if (glm::dot(d, d) <= 1e-30f * std::max(1.0f, glm::dot(c.position, c.position))) throw Error(where + ": the camera's target is at its position");
  if (glm::dot(c.up, c.up) == 0.0f) throw Error(where + ": the camera's up vector is zero");
  if (!(c.yfov > 0.0f && c.yfov < 3.14159f)) throw Error(where + ": the camera's field of view " + std::to_string(c.yfov) + " is not within (0, pi)");
  if (!(c.znear > 0.0f && c.zfar > c.znear)) throw Error(where + ": the camera needs 0 < znear < zfar, got " + std::to_string(c.znear) + " and " + std::to_string(c.zfar));
}

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

float defaultFlythroughHeight(const Camera& start) { return (start.position.y - start.target.y) / 3.0f; }

Camera flythroughCamera(const Camera& start, uint32_t frame, uint32_t frameCount, FlythroughShape shape) {
  Camera c = start;
  const float t = frameCount > 1 ? float(frame) / float(frameCount - 1) : 0.0f;
  const glm::vec3 offset = start.position - start.target;
  // From the start, over the target at a third of the start's height (or the shape's), out
  // to the far side at 0.6 of the distance, swaying sideways; looking a little ahead of the
  // target's height (or at the target).
  const float overHeight = shape.overHeight > 0.0f ? shape.overHeight : defaultFlythroughHeight(start);
  const glm::vec3 far = start.target + glm::vec3(-0.6f * offset.x, std::max(0.6f * offset.y, overHeight), -0.6f * offset.z);
  const glm::vec3 over = start.target + glm::vec3(0.0f, overHeight, 0.0f);
  const glm::vec3 along = t < 0.5f ? glm::mix(start.position, over, 2.0f * t) : glm::mix(over, far, 2.0f * t - 1.0f);
  glm::vec3 side = glm::cross(offset, start.up);
  side = glm::length(side) > 0.0f ? glm::normalize(side) : glm::vec3(1.0f, 0.0f, 0.0f);
  c.position = along + side * (0.25f * glm::length(offset) * std::sin(6.28318531f * t));
  if (shape.lookAtTarget) return c;  // start.target
  const glm::vec3 ahead = far - start.position;
  c.target = glm::vec3(c.position.x, start.target.y, c.position.z) + 0.5f * ahead;
  return c;
}

}  // namespace raybudget
