// Orders a batch of rays so that neighbours share a direction and a region: the batch
// tracer then hands each SIMD group (8 lanes on lavapipe, 32 on a GPU) rays that walk the
// same nodes, and its lanes idle less while the slowest one finishes. Incoherent rays
// (one random bounce per pixel) gain most: docs/TRACER.md has the figures.
#pragma once
#include <cstdint>
#include <vector>

#include "shared/bvh.h"

namespace raybudget::bvh {

// The bin of a ray: its direction quantised to 4 cells per axis (6 bits), then the Morton
// code of its origin on an 8x8x8 grid over [originMin, originMax] (9 bits).
uint32_t rayBinKey(const gpu::GpuRay& ray, const glm::vec3& originMin, const glm::vec3& originMax);
inline constexpr uint32_t kRayBinCount = 1u << 15;

// A permutation of [0, rays.size()) that lists the rays bin by bin (a counting sort, stable
// within a bin: O(n), about 20 ms for 10^6 rays on one core).
std::vector<uint32_t> binRays(const std::vector<gpu::GpuRay>& rays);

}  // namespace raybudget::bvh
