// Defaults for what a scene may leave out (lights, camera) and the K/Q/I checks.
#include <cmath>

#include "raybudget/error.h"
#include "raybudget/scene.h"

namespace raybudget {

Light defaultSun() {
  Light l;
  l.name = "raybudget-default-sun";
  l.type = LightType::Directional;
  l.color = glm::vec3(1.0f, 0.96f, 0.9f);
  l.intensity = 3.0f;
  l.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.4f));
  return l;
}

Camera defaultCamera(const Scene& scene, float aspect) {
  if (scene.camera) return *scene.camera;
  // Frame the bounding sphere from the front (+z), a little above, with some margin.
  const glm::vec3 center = 0.5f * (scene.boundsMin + scene.boundsMax);
  const float radius = std::max(0.5f * glm::length(scene.boundsMax - scene.boundsMin), 1e-3f);
  Camera c;
  c.yfov = 0.7f;
  const float halfFov = 0.5f * std::min(c.yfov, 2.0f * std::atan(std::tan(0.5f * c.yfov) * aspect));
  const float distance = radius / std::sin(halfFov) * 1.05f;
  const glm::vec3 dir = glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));
  c.target = center;
  c.position = center + dir * distance;
  c.znear = std::max(distance - radius * 1.5f, distance * 1e-3f);
  c.znear = std::max(std::min(c.znear, distance - radius), distance * 1e-3f);
  c.zfar = distance + radius * 2.0f;
  return c;
}

void validateRayBudgetParams(const RayBudgetParams& params, const std::string& where) {
  auto check = [&](const std::optional<float>& v, const char* name) {
    if (!v) return;
    if (!std::isfinite(*v)) throw Error(where + ": " + name + " is not finite");
    if (*v < 0.0f) throw Error(where + ": " + name + " = " + std::to_string(*v) + " is negative");
    if (*v > kMaxParamValue)
      throw Error(where + ": " + name + " = " + std::to_string(*v) + " exceeds the maximum " + std::to_string(kMaxParamValue));
  };
  check(params.importanceK, "K");
  check(params.raysQ, "Q");
  check(params.hysteresisI, "I");
}

}  // namespace raybudget
