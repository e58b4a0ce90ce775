// Traces a batch of rays from a buffer on the GPU with the compute tracer
// (shaders/trace_rays.comp): the oracle tests compare its hits with Embree's, and the
// throughput benchmark times it with GPU timestamps.
#pragma once
#include <memory>
#include <vector>

#include "bvh/scene_bvh.h"
#include "shared/bvh.h"
#include "vk/context.h"

namespace raybudget::passes {

class BatchTracer {
 public:
  BatchTracer(const vk::Context& ctx, const bvh::SceneBvh& bvh);
  ~BatchTracer();
  BatchTracer(const BatchTracer&) = delete;
  BatchTracer& operator=(const BatchTracer&) = delete;

  // Traces `rays` with RB_RQ_* `flags`; every candidate is accepted.
  std::vector<gpu::GpuHit> trace(const std::vector<gpu::GpuRay>& rays, uint32_t flags);
  // GPU milliseconds of the last trace's dispatch (timestamps).
  double lastGpuMs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raybudget::passes
