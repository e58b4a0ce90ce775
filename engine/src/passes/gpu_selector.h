// The selection policies on the GPU: sort keys, a bitonic sort (two orders for `paper`)
// and the sequential walk (shaders/select/). Owns its buffers, sized for `capacity`
// candidates, and its descriptor set. engine/src/select/policies.h is the CPU reference it
// reproduces exactly; `optimal` is CPU-only (benchmarks).
#pragma once
#include <memory>
#include <span>

#include "select/policies.h"
#include "vk/context.h"

namespace raybudget::passes {

class GpuSelector {
 public:
  GpuSelector(const vk::Context& ctx, uint32_t capacity);
  ~GpuSelector();
  GpuSelector(const GpuSelector&) = delete;
  GpuSelector& operator=(const GpuSelector&) = delete;

  // Uploads `candidates`, selects on the GPU, reads the selection back (waits). Throws
  // raybudget::Error for `optimal`, more candidates than the capacity, or bad input.
  select::Selection select(std::span<const select::Candidate> candidates, select::Policy policy, float budget,
                           const select::PolicyOptions& options = {});
  // GPU milliseconds of the last select() (keys, sort, walk; timestamps).
  double lastGpuMs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raybudget::passes
