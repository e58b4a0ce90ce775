// Defaults for what a scene may leave out (lights, camera) and the K/Q/I checks.
#include <cmath>
#include <limits>

#include "raybudget/error.h"
#include "raybudget/scene.h"
#include "scene/bounds.h"

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

Camera pathStartCamera(const Scene& scene, float aspect) {
  Camera c = defaultCamera(scene, aspect);
  const glm::vec3 center = 0.5f * (scene.boundsMin + scene.boundsMax);
  c.position = center + 0.6f * (c.position - center);
  c.target = center;
  // The default camera's near plane sits just short of the bounds from its own distance;
  // 40% closer it would cut through the scene (a single object's front clipped away, its
  // inside shown), and the paths go on into the bounds: a near plane at a hundredth of the
  // scene's radius clips nothing the paths look at. (D32F depth keeps zfar / znear ~ 500.)
  const float radius = std::max(0.5f * glm::length(scene.boundsMax - scene.boundsMin), 1e-3f);
  c.znear = std::min(c.znear, 0.01f * radius);
  c.up = glm::vec3(0.0f, 1.0f, 0.0f);
  if (glm::length(glm::cross(c.position - c.target, c.up)) < 1e-6f) c.position.z += 1e-3f;  // straight above: lookAt needs a side
  return c;
}

namespace {
// Whether some triangle of `object` lies straight above `p`: p is under its surface (inside a
// closed model, or under a roof), not in the open between walls.
bool coveredBy(const Scene& scene, const Object& object, const glm::vec3& p) {
  const Mesh& mesh = scene.meshes[object.mesh];
  auto world = [&](uint32_t i) { return glm::vec3(object.transform * glm::vec4(mesh.vertices[i].position, 1.0f)); };
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 a = world(mesh.indices[t]), b = world(mesh.indices[t + 1]), c = world(mesh.indices[t + 2]);
    // Barycentrics of p in the triangle's projection on the ground plane.
    const glm::vec2 e1(b.x - a.x, b.z - a.z), e2(c.x - a.x, c.z - a.z), d(p.x - a.x, p.z - a.z);
    const float det = e1.x * e2.y - e1.y * e2.x;
    if (std::fabs(det) < 1e-12f) continue;  // seen edge-on from above
    const float u = (d.x * e2.y - d.y * e2.x) / det, v = (e1.x * d.y - e1.y * d.x) / det;
    if (u >= 0.0f && v >= 0.0f && u + v <= 1.0f && a.y + u * (b.y - a.y) + v * (c.y - a.y) > p.y) return true;
  }
  return false;
}
}  // namespace

FlythroughShape flythroughShape(const Scene& scene, const Camera& start) {
  const glm::vec3 middle = start.target + glm::vec3(0.0f, defaultFlythroughHeight(start), 0.0f);
  float top = -std::numeric_limits<float>::infinity();
  for (const Object& o : scene.objects)
    if (glm::all(glm::greaterThanEqual(middle, o.boundsMin)) && glm::all(glm::lessThanEqual(middle, o.boundsMax)) && coveredBy(scene, o, middle))
      top = std::max(top, o.boundsMax.y);
  if (!std::isfinite(top)) return {};
  const float radius = 0.5f * glm::length(scene.boundsMax - scene.boundsMin);
  return {top - start.target.y + 0.05f * radius, true};
}

void validateTransform(const glm::mat4& transform, const std::string& where) {
  const float det = glm::determinant(glm::mat3(transform));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(transform[c][r]) || std::fabs(transform[c][r]) > 1.0e7f) throw Error(where + ": non-finite or absurd transform");
  if (!std::isfinite(det) || std::fabs(det) < 1e-30f) throw Error(where + ": singular transform");
}

glm::vec3 renderOrigin(const Scene& scene) {
  const glm::vec3 centre = 0.5f * (scene.boundsMin + scene.boundsMax);
  return glm::length(centre) > kRebaseDistance ? centre : glm::vec3(0.0f);
}

Scene inRenderSpace(const Scene& scene, const glm::vec3& origin) {
  if (origin == glm::vec3(0.0f)) return scene;
  Scene s = scene;
  for (Object& o : s.objects) {
    o.transform = inRenderSpace(o.transform, origin);
    worldBounds(s.meshes[o.mesh], o.transform, o.boundsMin, o.boundsMax);
  }
  for (Light& l : s.lights) l.position -= origin;
  for (ReflectionProbe& p : s.reflectionProbes) {
    p.center -= origin;
    p.boxMin -= origin;
    p.boxMax -= origin;
  }
  if (s.camera) s.camera = inRenderSpace(*s.camera, origin);
  updateSceneBounds(s);
  return s;
}

Camera inRenderSpace(const Camera& camera, const glm::vec3& origin) {
  Camera c = camera;
  c.position -= origin;
  c.target -= origin;
  return c;
}

glm::mat4 inRenderSpace(const glm::mat4& transform, const glm::vec3& origin) {
  glm::mat4 t = transform;
  t[3] -= glm::vec4(origin, 0.0f);
  return t;
}

void setObjectTransform(Scene& scene, uint32_t id, const glm::mat4& transform) {
  if (id >= scene.objects.size()) throw Error("setObjectTransform: object " + std::to_string(id) + " does not exist");
  validateTransform(transform, "setObjectTransform: object " + std::to_string(id));
  Object& o = scene.objects[id];
  const Mesh& m = scene.meshes[o.mesh];
  o.transform = transform;
  worldBounds(m, transform, o.boundsMin, o.boundsMax);
  updateSceneBounds(scene);
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
