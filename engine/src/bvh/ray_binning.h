// Orders a batch of rays so that neighbours share a direction and a region: the batch
// tracer then hands each SIMD group (8 lanes on lavapipe, 32 on a GPU) rays that walk the
// same nodes, and its lanes idle less while the slowest one finishes. It pays for
// incoherent rays (one random bounce per pixel) on small and mid-size scenes and can lose
// where the caller's order already kept a large BVH in cache: docs/TRACER.md has figures.
#pragma once
#include <cstdint>
#include <vector>

#include "shared/bvh.h"

namespace raybudget::bvh {

// The bin of a ray: the Morton code of its origin on a 16x16x16 grid over
// [originMin, originMax] (12 bits), then its direction quantised to 4 cells per axis
// (6 bits). Origin first keeps rays that start close together (and read the same nodes:
// the cache) in one run; direction within it gives the SIMD group rays that walk alike.
uint32_t rayBinKey(const gpu::GpuRay& ray, const glm::vec3& originMin, const glm::vec3& originMax);
inline constexpr uint32_t kRayBinCount = 1u << 18;

// Orders rays bin by bin: a counting sort, stable within a bin, O(n). Keeps its buffers
// between calls (a batch tracer bins every batch; fresh megabytes cost page faults).
class RayBinner {
 public:
  // A permutation of [0, rays.size()); valid until the next call.
  const std::vector<uint32_t>& bin(const std::vector<gpu::GpuRay>& rays);

 private:
  std::vector<uint32_t> keys_, start_, order_;
};

// The same, with buffers of its own.
std::vector<uint32_t> binRays(const std::vector<gpu::GpuRay>& rays);

}  // namespace raybudget::bvh
