// The selection policies on the GPU: sort keys, a sort (two orders for `paper`)
// and the sequential walk (shaders/select/). Owns its buffers, sized for `capacity`
// candidates, and its descriptor set. engine/src/select/policies.h is the CPU reference it
// reproduces exactly; `optimal` is CPU-only (benchmarks).
#pragma once
#include <memory>
#include <span>

#include "select/cost_model.h"
#include "select/policies.h"
#include "shared/selection.h"
#include "vk/context.h"

namespace raybudget::select {

// How the candidates are ordered: a bitonic sort in shared-memory blocks, or a merge sort
// (blocks sorted by one-subgroup workgroups, then barrier-free merge passes: faster on a CPU
// device, where barriers between SIMD batches are expensive). Auto picks the merge sort on
// a CPU device. Both give the same order.
enum class SortMethod { Auto, Bitonic, Merge };

// What `benefit` needs of the frame: the effects traced (RB_RT_* bits), the scene's light
// count, the pixels on screen, the parts left out (RB_BENEFIT_* bits: ablations), the probe's
// budget (in the budget's units; 0: no probe), the rate selected items are traced at.
struct ItemFrame {
  uint32_t effects = 0, lights = 0, pixels = 0, ablation = 0;
  float probeBudget = 0.0f;  // the sparse probe's share of the budget (shared/selection.h)
  uint32_t rate = RB_RATE_FULL;
  FrameFillQualities qualities = priorFillQualities();  // how well each effect's fill keeps a rate's value
  FillStill still;  // how far a still view moved the reflections' and refractions' qualities (itemFillQuality)
};

class GpuSelector {
 public:
  GpuSelector(const vk::Context& ctx, uint32_t capacity, SortMethod sort = SortMethod::Auto);
  ~GpuSelector();
  GpuSelector(const GpuSelector&) = delete;
  GpuSelector& operator=(const GpuSelector&) = delete;

  // Uploads `candidates`, selects on the GPU, reads the selection back (waits). Throws
  // raybudget::Error for `optimal`, more candidates than the capacity, or bad input.
  Selection select(std::span<const Candidate> candidates, Policy policy, float budget,
                           const PolicyOptions& options = {});
  // GPU milliseconds of the last select() (keys, sort, walk; timestamps).
  double lastGpuMs() const;
  // The walk's own sums of what the last select() selected (frame mode reports these).
  struct WalkSums {
    float cost = 0.0f, value = 0.0f;
  };
  WalkSums lastWalkSums() const;

  // Frame mode. The renderer's per-object buffers (shared/selection.h): records in, the
  // selection out (uint per object, written here), K/Q/I with S updated for the next frame,
  // the learned costs per object; for `benefit` the coverage counts and the items' state.
  struct FrameBuffers {
    VkBuffer records, selection, params, costs, coverage, items;
  };
  void bindFrame(const FrameBuffers& buffers);
  // The frame's time scale: ms per unit of work (kappa), and the work a ray costs, which
  // prices what was never traced (TimeScale::priorWorkPerRay).
  struct FrameScale {
    float kappa = 0.0f, workPerRay = 0.0f;
  };
  // Records, into the frame's command buffer, the selection among the objects' candidates
  // with costs kappa * work (cost_model.h: the paper's C for `paper`, else pixels times the
  // learned work per pixel, or before that rays times the work per ray). Afterwards
  // resultBuffer() holds uvec4(candidates, predicted cost bits (with `benefit`, the probe's
  // included), value bits, selected) and
  // uvec4(objects whose selection changed, the candidates' total cost in 2^-20 budget
  // units (lo, hi), 1 when the selection needed the sort).
  // With `benefit` the candidates are items (object * RB_ITEMS_PER_OBJECT + effect); the
  // capacity must hold RB_ITEMS_PER_OBJECT per object.
  void recordFrame(VkCommandBuffer cmd, uint32_t objects, Policy policy, float budget, FrameScale scale,
                   const PolicyOptions& options, const ItemFrame& items = {}) const;
  static constexpr uint32_t kResultBytes = 64;  // select_common.glsl's ResultBlock: 16 words
  VkBuffer resultBuffer() const;
  // The frame's candidates (GpuCandidate, resultBuffer().x of them) for CPU-side stats.
  VkBuffer candidateBuffer() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raybudget::select
