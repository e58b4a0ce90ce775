// The heuristic's per-object pass: coverage of the object-ID buffer (shaders/select/coverage.comp)
// then A, P, D, V, C, R per object (shaders/select/object_metrics.comp) into the object records.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::select {

class CoveragePass {
 public:
  CoveragePass(const vk::Context& ctx, passes::PassLayouts& layouts);
  // Clears the coverage, counts (and with `classify` the classifier's reflection and
  // refraction pixels, else 0), then computes the records; barriers included. `reuse`: the
  // coverage buffers hold what the frame before counted on the same view, objects and
  // classifier (a still view: Context decides), so only the records are computed again (their
  // R holds this frame's S) and the stage's clock starts there.
  void record(const passes::FrameContext& fc, bool classify, bool reuse) const;

 private:
  const passes::PassLayout& layout_;
  vk::Owned<VkPipeline> coverage_;
  vk::Owned<VkPipeline> classifying_;  // with the classifier
  vk::Owned<VkPipeline> metrics_;
};

}  // namespace raybudget::select
