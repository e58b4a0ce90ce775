// A compute pass over the screen in RB_TILE_SIZE tiles: lighting (with the environment
// reflection/refraction fallback), compose and the behind-glass copy are each one of these
// with its own shader.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"
#include "vk/pipelines.h"

namespace raybudget::passes {

class ScreenPass {
 public:
  ScreenPass(const vk::Context& ctx, PassLayouts& layouts, vk::Spirv shader);
  // Dispatches over every pixel in pass mode `mode`; the caller places the barriers between passes.
  void record(const FrameContext& fc, uint32_t mode = 0) const;
  // Over every `stride`-th pixel of the rectangle [x0, x1) x [y0, y1), in pass mode `mode`
  // (shaders/include/screen_pixel.glsl).
  void recordOver(const FrameContext& fc, uint32_t mode, const glm::uvec4& rect, uint32_t stride) const;

 private:
  const PassLayout& layout_;
  vk::Owned<VkPipeline> pipeline_;
};

}  // namespace raybudget::passes
