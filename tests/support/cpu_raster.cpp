#include "support/cpu_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace raybudget::test {
namespace {

constexpr uint32_t kNone = 0xFFFFFFFFu;

// Clips a polygon in clip space against z >= 0 (Vulkan's near plane).
std::vector<glm::vec4> clipNear(const std::vector<glm::vec4>& poly) {
  std::vector<glm::vec4> out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::vec4& a = poly[i];
    const glm::vec4& b = poly[(i + 1) % poly.size()];
    const bool ina = a.z >= 0.0f, inb = b.z >= 0.0f;
    if (ina) out.push_back(a);
    if (ina != inb) out.push_back(a + (b - a) * (a.z / (a.z - b.z)));
  }
  return out;
}

}  // namespace

CpuIdImage rasterizeObjectIds(const Scene& scene, const Camera& camera, uint32_t width, uint32_t height) {
  CpuIdImage img;
  img.width = width;
  img.height = height;
  img.ids.assign(size_t(width) * height, kNone);
  img.alphaTested.assign(size_t(width) * height, 0);
  std::vector<float> depth(size_t(width) * height, std::numeric_limits<float>::infinity());
  const glm::mat4 viewProj = camera.projection(float(width) / float(height)) * camera.view();
  for (const Object& o : scene.objects) {
    const Mesh& mesh = scene.meshes[o.mesh];
    const glm::mat4 m = viewProj * o.transform;
    for (const Primitive& p : mesh.primitives) {
      const bool masked = scene.materials[size_t(p.material)].alphaMode == AlphaMode::Mask;
      for (uint32_t t = p.firstIndex; t + 2 < p.firstIndex + p.indexCount; t += 3) {
        std::vector<glm::vec4> poly;
        for (int k = 0; k < 3; ++k) poly.push_back(m * glm::vec4(mesh.vertices[mesh.indices[t + uint32_t(k)]].position, 1.0f));
        poly = clipNear(poly);
        if (poly.size() < 3) continue;
        std::vector<glm::vec3> s;  // pixel x, pixel y, depth
        for (const glm::vec4& c : poly)
          s.push_back({(c.x / c.w * 0.5f + 0.5f) * float(width), (c.y / c.w * 0.5f + 0.5f) * float(height), c.z / c.w});
        for (size_t k = 1; k + 1 < s.size(); ++k) {  // fan of the clipped polygon
          const glm::vec3 a = s[0], b = s[k], c = s[k + 1];
          const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
          if (area == 0.0f) continue;
          const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
          const int x1 = std::min(int(width) - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
          const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
          const int y1 = std::min(int(height) - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
          for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
              const float px = float(x) + 0.5f, py = float(y) + 0.5f;
              const float w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
              const float w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
              const float w2 = 1.0f - w0 - w1;
              if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) continue;
              const float z = w0 * a.z + w1 * b.z + w2 * c.z;  // z/w is affine in screen space
              const size_t i = size_t(y) * width + size_t(x);
              if (z < 0.0f || z > 1.0f || z >= depth[i]) continue;
              depth[i] = z;
              img.ids[i] = o.id;
              img.alphaTested[i] = masked ? 1 : 0;
            }
        }
      }
    }
  }
  return img;
}

IdComparison compareIds(const CpuIdImage& cpu, const std::vector<uint32_t>& gpu) {
  IdComparison r;
  r.pixels = cpu.ids.size();
  const int w = int(cpu.width), h = int(cpu.height);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      if (cpu.ids[i] != kNone) ++r.covered;
      if (cpu.alphaTested[i]) {
        ++r.ignored;
        continue;
      }
      if (cpu.ids[i] == gpu[i]) continue;
      ++r.mismatches;
      bool interior = true;
      for (int dy = -1; dy <= 1 && interior; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = std::clamp(x + dx, 0, w - 1), ny = std::clamp(y + dy, 0, h - 1);
          if (cpu.ids[size_t(ny) * size_t(w) + size_t(nx)] != cpu.ids[i]) {
            interior = false;
            break;
          }
        }
      if (interior) ++r.interiorMismatches;
    }
  return r;
}

}  // namespace raybudget::test
