// Embree as the oracle (and the CPU speed reference): the scene's triangles in world space
// in one Embree geometry, traced with rtcIntersect1 / rtcOccluded1 and their 8-ray packets.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "raybudget/scene.h"

namespace raybudget::bvh {

struct OracleHit {
  bool hit = false;
  float t = 0.0f;
  uint32_t object = 0;
  uint32_t primitive = 0;  // triangle index within the object's mesh
  glm::vec2 barycentrics{0.0f};
};

struct OracleRay {
  glm::vec3 origin;
  float tMin;
  glm::vec3 dir;
  float tMax;
};

class EmbreeOracle {
 public:
  explicit EmbreeOracle(const Scene& scene);
  ~EmbreeOracle();
  EmbreeOracle(const EmbreeOracle&) = delete;
  EmbreeOracle& operator=(const EmbreeOracle&) = delete;

  OracleHit intersect(const OracleRay& ray) const;
  bool occluded(const OracleRay& ray) const;
  // Packets of 8 (the last may be partial), for the throughput comparison.
  void intersect8(const OracleRay* rays, size_t count, OracleHit* hits) const;
  void occluded8(const OracleRay* rays, size_t count, bool* blocked) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raybudget::bvh
