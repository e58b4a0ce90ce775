// Screen-space reflections, the reflection fallback's first choice: the G-buffer's depth into
// a min-depth pyramid, then each smooth surface's mirror ray marched through it, reading the
// previous frame's image where it meets a surface (shaders/ssr.comp). Pipelines are built on
// the first frame that records the pass.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::passes {

class ScreenReflectionPass {
 public:
  ScreenReflectionPass(const vk::Context& ctx, PassLayouts& layouts);
  void record(const FrameContext& fc);
  bool built() const { return bool(pyramid_); }
  // Before the first frame: the pyramid and the result into GENERAL, where they stay.
  static void initialize(VkCommandBuffer cmd, const FrameTargets& t);

 private:
  const vk::Context& ctx_;
  const PassLayout& layout_;
  vk::Owned<VkPipeline> pyramid_;
  vk::Owned<VkPipeline> march_;
};

}  // namespace raybudget::passes
