// Deterministic ray sets for the tracer tests and benchmarks: primary rays of a camera in 8x8
// tile order, shadow rays from primary hits to a point, and incoherent rays (one random
// hemisphere direction per primary hit).
#pragma once
#include <cstdint>
#include <vector>

#include "bvh/embree_oracle.h"
#include "raybudget/camera.h"
#include "raybudget/scene.h"
#include "shared/bvh.h"

namespace raybudget::bvh {

std::vector<OracleRay> primaryRays(const Camera& camera, uint32_t width, uint32_t height);

// From each primary hit, offset along the geometric normal, towards `light` (shadow) or a
// cosine-distributed direction about the normal (incoherent); misses produce no ray.
struct SecondaryRays {
  std::vector<OracleRay> shadow;
  std::vector<OracleRay> incoherent;
};
SecondaryRays secondaryRays(const Scene& scene, const EmbreeOracle& oracle, const std::vector<OracleRay>& primary,
                            const glm::vec3& light, uint32_t seed);

// The same rays in the batch tracer's layout (shared/bvh.h).
std::vector<gpu::GpuRay> toGpuRays(const std::vector<OracleRay>& rays);

// Small deterministic generator (PCG-style hash), the same on every platform.
struct Rng {
  uint64_t state;
  explicit Rng(uint64_t seed) : state(seed * 6364136223846793005ull + 1442695040888963407ull) {}
  float next() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return float(uint32_t(state >> 40)) / float(1u << 24);
  }
};

}  // namespace raybudget::bvh
