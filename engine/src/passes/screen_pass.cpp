#include "passes/screen_pass.h"

#include "passes/frame_targets.h"
#include "shared/config.h"
#include "shared/types.h"
#include "vk/pipelines.h"

namespace raybudget::passes {

ScreenPass::ScreenPass(const vk::Context& ctx, PassLayouts& layouts, vk::Spirv shader)
    : layout_(layouts.create({shader})), pipeline_(vk::createComputePipeline(ctx, layout_.pipelineLayout, shader)) {}

void ScreenPass::record(const FrameContext& fc, uint32_t argument) const {
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  gpu::DrawPush push{};
  push.objectMaterial.x = argument;
  layout_.push(fc, push);
  vkCmdDispatch(fc.cmd, vk::groupsFor(fc.targets.width, RB_TILE_SIZE), vk::groupsFor(fc.targets.height, RB_TILE_SIZE), 1);
}

}  // namespace raybudget::passes
