#include "bvh/ray_sets.h"

#include <cmath>

#include "shared/offset_ray.h"

namespace raybudget::bvh {

std::vector<OracleRay> primaryRays(const Camera& camera, uint32_t width, uint32_t height) {
  std::vector<OracleRay> rays;
  const glm::mat4 inv = glm::inverse(camera.projection(float(width) / float(height)) * camera.view());
  for (uint32_t ty = 0; ty < height; ty += 8)
    for (uint32_t tx = 0; tx < width; tx += 8)
      for (uint32_t y = ty; y < std::min(ty + 8, height); ++y)
        for (uint32_t x = tx; x < std::min(tx + 8, width); ++x) {
          const glm::vec2 ndc((float(x) + 0.5f) / float(width) * 2.0f - 1.0f, (float(y) + 0.5f) / float(height) * 2.0f - 1.0f);
          const glm::vec4 far = inv * glm::vec4(ndc, 1.0f, 1.0f);
          const glm::vec3 dir = glm::normalize(glm::vec3(far) / far.w - camera.position);
          rays.push_back({camera.position, 0.0f, dir, 1e30f});
        }
  return rays;
}

SecondaryRays secondaryRays(const Scene& scene, const EmbreeOracle& oracle, const std::vector<OracleRay>& primary,
                            const glm::vec3& light, uint32_t seed) {
  SecondaryRays out;
  Rng rng(seed);
  for (const OracleRay& r : primary) {
    const OracleHit h = oracle.intersect(r);
    if (!h.hit) continue;
    const Object& o = scene.objects[h.object];
    const Mesh& m = scene.meshes[o.mesh];
    glm::vec3 v[3];
    for (int k = 0; k < 3; ++k) v[k] = glm::vec3(o.transform * glm::vec4(m.vertices[m.indices[h.primitive * 3 + uint32_t(k)]].position, 1.0f));
    glm::vec3 n = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
    if (glm::dot(n, r.dir) > 0.0f) n = -n;
    const glm::vec3 p = (1.0f - h.barycentrics.x - h.barycentrics.y) * v[0] + h.barycentrics.x * v[1] + h.barycentrics.y * v[2];
    const glm::vec3 origin = gpu::offsetRay(p, n);
    const glm::vec3 toLight = light - origin;
    out.shadow.push_back({origin, 0.0f, glm::normalize(toLight), glm::length(toLight)});
    // Cosine-weighted direction about n.
    const float u1 = rng.next(), u2 = rng.next();
    const float radius = std::sqrt(u1), phi = 6.28318531f * u2;
    const glm::vec3 t = glm::normalize(std::fabs(n.x) > 0.9f ? glm::cross(n, glm::vec3(0, 1, 0)) : glm::cross(n, glm::vec3(1, 0, 0)));
    const glm::vec3 b = glm::cross(n, t);
    const glm::vec3 d = glm::normalize(t * (radius * std::cos(phi)) + b * (radius * std::sin(phi)) + n * std::sqrt(std::max(0.0f, 1.0f - u1)));
    out.incoherent.push_back({origin, 0.0f, d, 1e30f});
  }
  return out;
}

std::vector<gpu::GpuRay> toGpuRays(const std::vector<OracleRay>& rays) {
  std::vector<gpu::GpuRay> out;
  out.reserve(rays.size());
  for (const OracleRay& r : rays) out.push_back({glm::vec4(r.origin, r.tMin), glm::vec4(r.dir, r.tMax)});
  return out;
}

}  // namespace raybudget::bvh
