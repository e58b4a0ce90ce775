// A compute pass over the screen in RB_TILE_SIZE tiles: lighting, the environment
// reflection/refraction fallback and compose are each one of these with its own shader.
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
  // Dispatches over every tile with `argument` in DrawPush.objectMaterial.x; the caller
  // places the barriers between passes.
  void record(const FrameContext& fc, uint32_t argument = 0) const;

 private:
  const PassLayout& layout_;
  vk::Owned<VkPipeline> pipeline_;
};

}  // namespace raybudget::passes
