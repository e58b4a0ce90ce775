#include "scene/triangles.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace raybudget {

bool zeroAreaTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 e1 = b - a, e2 = c - a;
  const float l1 = glm::dot(e1, e1), l2 = glm::dot(e2, e2);
  const glm::vec3 n = glm::cross(e1, e2);
  // Relative test: sin^2 of the angle between the edges below 1e-14 means no area at
  // float precision, whatever the triangle's scale.
  return l1 == 0.0f || l2 == 0.0f || glm::dot(n, n) <= 1e-14f * l1 * l2;
}

std::vector<uint32_t> dropZeroAreaTriangles(std::span<const glm::vec3> positions, std::span<const uint32_t> triangles, size_t& dropped) {
  std::vector<uint32_t> kept;
  kept.reserve(triangles.size());
  dropped = 0;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const uint32_t a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    if (zeroAreaTriangle(positions[a], positions[b], positions[c])) {
      ++dropped;
      continue;
    }
    kept.insert(kept.end(), {a, b, c});
  }
  return kept;
}

std::vector<glm::vec3> areaWeightedNormals(std::span<const glm::vec3> positions, std::span<const uint32_t> triangles) {
  std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const glm::vec3 a = positions[triangles[t]], b = positions[triangles[t + 1]], c = positions[triangles[t + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    for (size_t k = 0; k < 3; ++k) normals[triangles[t + k]] += n;
  }
  return normals;
}

bool closedSurface(std::span<const glm::vec3> positions, std::span<const uint32_t> triangles) {
  if (triangles.size() < 3) return false;
  // Welded vertex IDs: the first vertex at each position, compared by bits (-0 and 0 apart,
  // as a mesh's seams repeat a position exactly).
  struct Bits {
    uint32_t v[3];
    bool operator==(const Bits&) const = default;
  };
  struct Hash {
    size_t operator()(const Bits& b) const { return (size_t(b.v[0]) * 73856093u) ^ (size_t(b.v[1]) * 19349663u) ^ (size_t(b.v[2]) * 83492791u); }
  };
  std::unordered_map<Bits, uint32_t, Hash> first;
  auto weld = [&](uint32_t i) {
    Bits b;
    std::memcpy(b.v, &positions[i], sizeof b.v);
    return first.try_emplace(b, uint32_t(first.size())).first->second;
  };
  std::unordered_map<uint64_t, uint32_t> edgeUses;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const uint32_t a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    if (zeroAreaTriangle(positions[a], positions[b], positions[c])) continue;
    const uint32_t w[3] = {weld(a), weld(b), weld(c)};
    for (int e = 0; e < 3; ++e) {
      const uint32_t lo = std::min(w[e], w[(e + 1) % 3]), hi = std::max(w[e], w[(e + 1) % 3]);
      ++edgeUses[(uint64_t(lo) << 32) | hi];
    }
  }
  if (edgeUses.empty()) return false;
  return std::all_of(edgeUses.begin(), edgeUses.end(), [](const auto& e) { return e.second % 2 == 0; });
}

}  // namespace raybudget
