// The selection half of the ray-tracing stage, on the GPU: coverage (per-object A..R, the
// tiles' objects), the policy's choice within the budget (or none / all), the tile list the
// trace passes dispatch over, and the cost model that predicts what they will cost. The
// renderer records it into each frame and hands it each frame's timestamps back.
#pragma once
#include <memory>
#include <vector>

#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "raybudget/renderer.h"
#include "select/policies.h"
#include "select/selection_buffers.h"
#include "vk/context.h"

namespace raybudget::select {

// The public policy's CPU reference (raybudget::Policy has no `optimal`).
select::Policy toSelectPolicy(raybudget::Policy policy);

class SelectionStage {
 public:
  // `checkAgainstCpu` (tests, raybudget/testing.h): read each frame's candidates, selection
  // and costs back and compare them with the CPU references (FrameTiming::selectionMatchesCpu).
  SelectionStage(const vk::Context& ctx, passes::PassLayouts& layouts, const Scene& scene, const RenderSettings& settings, uint32_t framesInFlight,
                 bool checkAgainstCpu = false);
  ~SelectionStage();
  SelectionStage(const SelectionStage&) = delete;
  SelectionStage& operator=(const SelectionStage&) = delete;

  const SelectionBuffers& buffers() const;

  // Starts frame slot `slot`: nothing selected until recordSelect; K, Q and I changed since
  // the last frame are uploaded first (a transfer and a barrier before every later read).
  void beginFrame(VkCommandBuffer cmd, uint32_t slot);
  // An object's K, Q, I from the next frame on (and after restarts); S stays the GPU's.
  void setObjectParams(uint32_t object, float K, float Q, float I);
  // Whether frame slot `slot` leaves the whole stage (coverage, select, trace) out: a budgeted
  // policy whose T is at or below the stage's fixed cost, learned from at least three frames.
  // Every kRemeasureEvery-th frame in a row runs it anyway, so that a fixed cost that fell
  // (or one learned from a slow start) is found out. Called once per frame, before the passes.
  bool skipsStage(uint32_t slot, const RenderSettings& settings);
  static constexpr uint32_t kRemeasureEvery = 32;
  // The coverage pass (with `classify`, the classifier's pixel counts too); barriers included.
  // `reuse`: the coverage buffers still hold this view's counts (CoveragePass::record).
  void recordCoverage(const passes::FrameContext& fc, bool classify, bool reuse) const;
  // The select pass for `slot`: with a budgeted policy the GPU selection within T less the
  // learned overhead (and the copies its stats need), else none / all; then the tile list,
  // ready for the trace passes' indirect dispatch. `stillFrames`: the frames before this one in
  // a row whose camera and objects were where they are now (rates priced for a still view's
  // temporal fill, shared/selection.h's RB_FILL_QUALITY_STILL).
  // `coverageReused`: this frame's coverage pass kept the frame before's counts (recordCoverage's
  // `reuse`), whose frames the stage's overhead is learned and predicted apart for.
  void recordSelect(const passes::FrameContext& fc, uint32_t slot, const RenderSettings& settings, uint32_t stillFrames, bool coverageReused);
  // The stage's deadlines for the frame's uniforms in device-clock ticks (stage_deadline.h), the
  // effects pass's (x), the shadow pass's (y) and the fill's (z): 0, none, unless a budgeted
  // policy learns its time scale with RenderSettings::stageDeadline.
  glm::uvec3 deadlineTicks(const RenderSettings& settings) const;
  // After the trace passes: the copy of the tile list's header (tiles and rays traced).
  void recordStats(VkCommandBuffer cmd, uint32_t slot) const;
  // After the slot's fence: the frame's selection stats into `t` (its pass times read), and
  // the cost model learns from them.
  void retire(uint32_t slot, const RenderSettings& settings, FrameTiming& t);

  // Forgets S and each object's learned work per pixel (the time scale stays); builds the
  // GPU selector if `settings` needs it first.
  void restart(const RenderSettings& settings);
  CostModel costModel() const;
  void setCostModel(const CostModel& model);  // values validated by the caller

  // The last frame's per-object records and selection (waits for the queue).
  std::vector<ObjectMetrics> objectMetrics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raybudget::select
