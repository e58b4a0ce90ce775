#include "support/procedural.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

namespace raybudget::test {
namespace {

void finish(Mesh& m) {
  m.primitives = {Primitive{0, uint32_t(m.indices.size()), 0}};
  m.boundsMin = m.boundsMax = m.vertices[0].position;
  for (const Vertex& v : m.vertices) {
    m.boundsMin = glm::min(m.boundsMin, v.position);
    m.boundsMax = glm::max(m.boundsMax, v.position);
  }
}

}  // namespace

Mesh icosphere(int subdivisions) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (glm::vec3& v : p) v = glm::normalize(v);
  std::vector<uint32_t> idx = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                               3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      p.push_back(glm::normalize(p[a] + p[b]));
      return mid[key] = uint32_t(p.size() - 1);
    };
    std::vector<uint32_t> next;
    for (size_t i = 0; i < idx.size(); i += 3) {
      const uint32_t a = idx[i], b = idx[i + 1], c = idx[i + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    idx.swap(next);
  }
  Mesh m;
  m.name = "icosphere";
  for (const glm::vec3& v : p) m.vertices.push_back(Vertex{v, v, {}, glm::vec4(1.0f)});
  m.indices = idx;
  finish(m);
  return m;
}

Mesh subdividedCube(int n) {
  Mesh m;
  m.name = "cube";
  std::map<std::tuple<int, int, int>, uint32_t> shared;  // lattice point -> vertex, so edges share vertices
  auto vertex = [&](int x, int y, int z) {
    const auto key = std::make_tuple(x, y, z);
    auto it = shared.find(key);
    if (it != shared.end()) return it->second;
    const glm::vec3 p = glm::vec3(float(x), float(y), float(z)) * (2.0f / float(n)) - glm::vec3(1.0f);
    m.vertices.push_back(Vertex{p, glm::normalize(p), {}, glm::vec4(1.0f)});
    return shared[key] = uint32_t(m.vertices.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side <= 1; ++side)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto lattice = [&](int a, int b) {
            int c[3];
            c[axis] = side * n;
            c[(axis + 1) % 3] = a;
            c[(axis + 2) % 3] = b;
            return vertex(c[0], c[1], c[2]);
          };
          const uint32_t v00 = lattice(i, j), v10 = lattice(i + 1, j), v11 = lattice(i + 1, j + 1), v01 = lattice(i, j + 1);
          if (side) m.indices.insert(m.indices.end(), {v00, v10, v11, v00, v11, v01});
          else m.indices.insert(m.indices.end(), {v00, v11, v10, v00, v01, v11});
        }
  finish(m);
  return m;
}

Mesh quad(float h) {
  Mesh m;
  m.name = "quad";
  for (const glm::vec3& p : {glm::vec3(-h, 0, -h), glm::vec3(h, 0, -h), glm::vec3(h, 0, h), glm::vec3(-h, 0, h)})
    m.vertices.push_back(Vertex{p, {0, 1, 0}, {}, glm::vec4(1.0f)});
  m.indices = {0, 2, 1, 0, 3, 2};
  finish(m);
  return m;
}

Mesh texturedQuad(float h) {
  Mesh m = quad(h);
  for (Vertex& v : m.vertices) v.uv = glm::vec2(v.position.x, v.position.z) / (2.0f * h) + 0.5f;
  return m;
}

int addFlatNormalMap(Scene& scene, glm::vec3 t) {
  const glm::vec3 c = glm::round((t * 0.5f + 0.5f) * 255.0f);
  Image img{"normals", 2, 2, {}};
  for (int i = 0; i < 4; ++i) img.rgba.insert(img.rgba.end(), {uint8_t(c.x), uint8_t(c.y), uint8_t(c.z), 255});
  scene.images.push_back(img);
  scene.textures.push_back(Texture{int(scene.images.size() - 1), -1});
  return int(scene.textures.size() - 1);
}

Mesh smallAndLargeTriangles(int perAxis, int large) {
  Mesh m;
  m.name = "small and large triangles";
  auto triangle = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (const glm::vec3& p : {a, b, c}) {
      m.vertices.push_back(Vertex{p, n, {}, glm::vec4(1.0f)});
      m.indices.push_back(uint32_t(m.vertices.size() - 1));
    }
  };
  const float step = 2.0f / float(perAxis), size = 0.3f * step;
  for (int i = 0; i < perAxis; ++i)
    for (int j = 0; j < perAxis; ++j)
      for (int k = 0; k < perAxis; ++k) {
        const glm::vec3 c = glm::vec3(-1.0f) + step * (glm::vec3(float(i), float(j), float(k)) + 0.5f);
        const glm::vec3 u = glm::normalize(glm::vec3(float(i % 3) - 1.0f, 1.0f, float(k % 2))), v = glm::normalize(glm::cross(u, glm::vec3(0.3f, 0.1f, 1.0f)));
        triangle(c - u * size, c + u * size, c + v * size);
      }
  for (int k = 0; k < large; ++k) {  // planes through the whole cube, each turned a little further
    const float a = 6.2831853f * float(k) / float(large), h = 0.9f * (float(k) / float(std::max(1, large - 1)) - 0.5f);
    const glm::vec3 d(std::cos(a), 0.0f, std::sin(a));
    triangle(-1.2f * d + glm::vec3(0, -1.2f, 0), 1.2f * d + glm::vec3(0, h, 0), glm::vec3(-d.z, 1.2f, d.x) * 1.2f);
  }
  finish(m);
  return m;
}

Material mirror(float roughness) {
  Material m;
  m.metallic = 1.0f;
  m.roughness = roughness;
  m.baseColorFactor = glm::vec4(1.0f);
  return m;
}

// A double-sided black emitter of `radiance`: what mirrors and glass show in tests.
Material emitter(const glm::vec3& radiance) {
  Material m;
  m.baseColorFactor = glm::vec4(0, 0, 0, 1);
  m.emissive = radiance;
  m.doubleSided = true;
  return m;
}

Material tintedGlass() {
  Material glass;
  glass.metallic = 0.0f;
  glass.roughness = 0.0f;
  glass.transmission = 1.0f;
  glass.ior = 1.5f;
  glass.thickness = 1.0f;
  glass.attenuationDistance = 1.0f;
  glass.attenuationColor = glm::vec3(0.5f, 1.0f, 1.0f);
  return glass;
}

void addObject(Scene& scene, Mesh mesh, const glm::mat4& transform, const Material& material) {
  scene.materials.push_back(material);
  for (Primitive& p : mesh.primitives) p.material = int32_t(scene.materials.size() - 1);
  scene.meshes.push_back(std::move(mesh));
  Object o;
  o.id = uint32_t(scene.objects.size());
  o.mesh = uint32_t(scene.meshes.size() - 1);
  o.transform = transform;
  o.boundsMin = glm::vec3(std::numeric_limits<float>::max());
  o.boundsMax = glm::vec3(-std::numeric_limits<float>::max());
  for (const Vertex& v : scene.meshes.back().vertices) {
    const glm::vec3 w = glm::vec3(transform * glm::vec4(v.position, 1.0f));
    o.boundsMin = glm::min(o.boundsMin, w);
    o.boundsMax = glm::max(o.boundsMax, w);
  }
  scene.boundsMin = scene.objects.empty() ? o.boundsMin : glm::min(scene.boundsMin, o.boundsMin);
  scene.boundsMax = scene.objects.empty() ? o.boundsMax : glm::max(scene.boundsMax, o.boundsMax);
  scene.objects.push_back(o);
  scene.stats.triangles += scene.meshes.back().indices.size() / 3;
}

Scene sceneWithMesh(Mesh mesh, const glm::mat4& transform) {
  Scene s;
  s.materials.push_back(Material{});
  s.meshes.push_back(std::move(mesh));
  Object o;
  o.mesh = 0;
  o.transform = transform;
  o.boundsMin = glm::vec3(std::numeric_limits<float>::max());
  o.boundsMax = glm::vec3(-std::numeric_limits<float>::max());
  for (const Vertex& v : s.meshes[0].vertices) {
    const glm::vec3 w = glm::vec3(transform * glm::vec4(v.position, 1.0f));
    o.boundsMin = glm::min(o.boundsMin, w);
    o.boundsMax = glm::max(o.boundsMax, w);
  }
  s.objects.push_back(o);
  s.boundsMin = o.boundsMin;
  s.boundsMax = o.boundsMax;
  s.lights.push_back(defaultSun());
  s.usesDefaultSun = true;
  return s;
}

Scene twoMirrors() {
  Scene scene;
  for (float x : {-1.0f, 1.0f}) addObject(scene, quad(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, 0.0f)), mirror());
  for (int side : {-1, 1})
    addObject(scene, quad(10.0f), glm::translate(glm::mat4(1.0f), glm::vec3(10.0f * float(side), 6.0f, -5.0f)),
              emitter(side < 0 ? glm::vec3(3.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 3.0f, 0.0f)));
  return scene;
}

}  // namespace raybudget::test
