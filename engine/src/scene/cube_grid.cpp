#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "raybudget/scene.h"

namespace raybudget {

Scene cubeGridScene(uint32_t n) {
  Scene s;
  s.path = "generated-" + std::to_string(n) + "-cubes";
  s.materials.push_back(Material{});
  Mesh cube;
  cube.name = "cube";
  for (int i = 0; i < 8; ++i) {
    Vertex v;
    v.position = glm::vec3(i & 1 ? 0.4f : -0.4f, i & 2 ? 0.8f : 0.0f, i & 4 ? 0.4f : -0.4f);
    v.normal = glm::normalize(v.position - glm::vec3(0.0f, 0.4f, 0.0f));
    cube.vertices.push_back(v);
  }
  cube.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  cube.primitives.push_back({0, uint32_t(cube.indices.size()), 0});
  cube.boundsMin = glm::vec3(-0.4f, 0.0f, -0.4f);
  cube.boundsMax = glm::vec3(0.4f, 0.8f, 0.4f);
  s.meshes.push_back(cube);
  const uint32_t side = uint32_t(std::ceil(std::sqrt(double(n))));
  for (uint32_t i = 0; i < n; ++i) {
    Object o;
    o.id = i;
    o.name = "cube" + std::to_string(i);
    const glm::vec3 at(float(i % side) - 0.5f * float(side), 0.0f, float(i / side) - 0.5f * float(side));
    o.transform = glm::translate(glm::mat4(1.0f), at);
    o.boundsMin = at + cube.boundsMin;
    o.boundsMax = at + cube.boundsMax;
    s.objects.push_back(o);
  }
  s.boundsMin = glm::vec3(-0.5f * float(side) - 0.4f, 0.0f, -0.5f * float(side) - 0.4f);
  s.boundsMax = glm::vec3(0.5f * float(side) + 0.4f, 0.8f, 0.5f * float(side) + 0.4f);
  s.lights.push_back(defaultSun());
  s.usesDefaultSun = true;
  return s;
}

}  // namespace raybudget
