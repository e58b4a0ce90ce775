// Traces a batch of rays from a buffer on the GPU (shaders/trace_rays.comp) with either
// tracer: our compute BVH or the device's VK_KHR_ray_query. The oracle tests compare its
// hits with Embree's, and the throughput benchmark times it with GPU timestamps.
#pragma once
#include <memory>
#include <vector>

#include "bvh/scene_bvh.h"
#include "raybudget/scene.h"
#include "shared/bvh.h"
#include "vk/context.h"

namespace raybudget::passes {

class BatchTracer {
 public:
  // The compute tracer over `bvh`.
  BatchTracer(const vk::Context& ctx, const bvh::SceneBvh& bvh);
  // The native tracer: builds Vulkan acceleration structures for `scene` (throws when the
  // device has no VK_KHR_ray_query).
  BatchTracer(const vk::Context& ctx, const Scene& scene);
  ~BatchTracer();
  BatchTracer(const BatchTracer&) = delete;
  BatchTracer& operator=(const BatchTracer&) = delete;

  // How trace() hands rays to the device: as given, or binned by origin and direction
  // first (bvh/ray_binning.h) so each SIMD group gets rays that walk the same nodes. The
  // hits come back in the caller's order either way, and each ray's hit is the same.
  enum class Order { AsGiven, Binned };

  // Traces `rays` with RB_RQ_* `flags`; every candidate is accepted.
  std::vector<gpu::GpuHit> trace(const std::vector<gpu::GpuRay>& rays, uint32_t flags, Order order = Order::AsGiven);
  // GPU milliseconds of the last trace's dispatch (timestamps).
  double lastGpuMs() const;
  // CPU milliseconds the last trace spent binning its rays (0 for Order::AsGiven).
  double lastBinMs() const;
  // Acceleration-structure build time (native: BLAS + TLAS on the device; compute: 0,
  // the CPU build happens before) and device memory it takes.
  double buildMs() const;
  size_t accelBytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raybudget::passes
