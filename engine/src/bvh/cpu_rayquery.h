// The CPU reference of the compute tracer: the same traversal source
// (shaders/shared/rayquery_traverse.h) compiled as C++ over a SceneBvh in memory.
#pragma once
#include <bit>

#include "bvh/scene_bvh.h"

namespace raybudget::bvh {
// The BVH the shared traversal code reads; set by CpuRayQueryScope.
inline thread_local const SceneBvh* currentBvh = nullptr;
}  // namespace raybudget::bvh

#define RB_BVH_NODE(i) (::raybudget::bvh::currentBvh->nodes[(i)])
#define RB_BVH_TRIANGLE(i) (::raybudget::bvh::currentBvh->triangles[(i)])
#define RB_BVH_INSTANCE(i) (::raybudget::bvh::currentBvh->instances[(i)])
#define RB_BVH_TLAS_ROOT RB_BVH_TLAS_ROOT_NODE
#include "shared/rayquery_traverse.h"

namespace raybudget::bvh {

// Makes `bvh` the one the ray-query functions read, for the scope's lifetime.
class CpuRayQueryScope {
 public:
  explicit CpuRayQueryScope(const SceneBvh& bvh) : previous_(currentBvh) { currentBvh = &bvh; }
  ~CpuRayQueryScope() { currentBvh = previous_; }
  CpuRayQueryScope(const CpuRayQueryScope&) = delete;
  CpuRayQueryScope& operator=(const CpuRayQueryScope&) = delete;

 private:
  const SceneBvh* previous_;
};

struct TraceResult {
  bool hit = false;
  float t = 0.0f;
  uint32_t object = 0;
  uint32_t primitive = 0;
  uint32_t material = 0;
  glm::vec2 barycentrics{0.0f};
  bool frontFace = false;
  uint32_t nodesVisited = 0;
  uint32_t trianglesTested = 0;
};

// Traces one ray, accepting every candidate (alpha-masked triangles count as hits).
inline TraceResult traceCpu(const SceneBvh& bvh, glm::vec3 origin, glm::vec3 dir, float tMin, float tMax, uint32_t flags) {
  CpuRayQueryScope scope(bvh);
  gpu::RayQuery q;
  gpu::rqInitialize(q, flags, 0xFFu, origin, tMin, dir, tMax);
  while (gpu::rqProceed(q)) gpu::rqConfirm(q);
  TraceResult r;
  r.hit = q.committedType == RB_RQ_HIT_TRIANGLE;
  r.t = q.tMax;
  r.object = q.committedObject;
  r.primitive = q.committedPrimitive;
  r.material = q.committedMaterial;
  r.barycentrics = q.committedBary;
  r.frontFace = q.committedFrontFace;
  r.nodesVisited = q.nodesVisited;
  r.trianglesTested = q.trianglesTested;
  return r;
}

}  // namespace raybudget::bvh
