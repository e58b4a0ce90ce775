// G-buffer pass: rasterises every visible object into depth, normal, base colour + metallic,
// roughness + transmission + IOR, emissive, object ID and material ID.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::passes {

class GBufferPass {
 public:
  GBufferPass(const vk::Context& ctx, PassLayouts& layouts);
  void record(const FrameContext& fc) const;

 private:
  const PassLayout& layout_;
  vk::Owned<VkPipeline> pipeline_;
};

}  // namespace raybudget::passes
