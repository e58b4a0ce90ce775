#include "passes/screen_reflections.h"

#include "depth_pyramid_comp.h"
#include "passes/frame_targets.h"
#include "shared/config.h"
#include "shared/types.h"
#include "ssr_comp.h"
#include "vk/pipelines.h"

namespace raybudget::passes {

ScreenReflectionPass::ScreenReflectionPass(const vk::Context& ctx, PassLayouts& layouts)
    : ctx_(ctx), layout_(layouts.create({kSpirv_depth_pyramid_comp, kSpirv_ssr_comp})) {}

void ScreenReflectionPass::initialize(VkCommandBuffer cmd, const FrameTargets& t) {
  for (const vk::Image* img : {&t.depthPyramid, &t.ssr})
    vk::imageBarrier(cmd, *img, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
}

void ScreenReflectionPass::record(const FrameContext& fc) {
  if (!pyramid_) {
    pyramid_ = vk::createComputePipeline(ctx_, layout_.pipelineLayout, kSpirv_depth_pyramid_comp);
    march_ = vk::createComputePipeline(ctx_, layout_.pipelineLayout, kSpirv_ssr_comp);
  }
  const FrameTargets& t = fc.targets;
  auto levelDone = [&] {
    vk::memoryBarrier(fc.cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  };
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pyramid_);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  // Levels 1.. into the pyramid's mips 0..: level 0 is the G-buffer's depth.
  for (uint32_t level = 1; level <= t.depthPyramidLevels.size(); ++level) {
    gpu::DrawPush push{};
    push.objectMaterial.x = level;
    layout_.push(fc, push);
    vkCmdDispatch(fc.cmd, vk::groupsFor(std::max(t.width >> level, 1u), RB_TILE_SIZE), vk::groupsFor(std::max(t.height >> level, 1u), RB_TILE_SIZE), 1);
    levelDone();
  }
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, march_);
  // One invocation per 2x2 quad (ssr.comp).
  vkCmdDispatch(fc.cmd, vk::groupsFor((t.width + 1) / 2, RB_TILE_SIZE), vk::groupsFor((t.height + 1) / 2, RB_TILE_SIZE), 1);
}

}  // namespace raybudget::passes
