#include "passes/screen_pass.h"

#include "passes/frame_targets.h"
#include "shared/config.h"
#include "shared/types.h"
#include "vk/pipelines.h"

namespace raybudget::passes {

ScreenPass::ScreenPass(const vk::Context& ctx, PassLayouts& layouts, vk::Spirv shader)
    : layout_(layouts.create({shader})), pipeline_(vk::createComputePipeline(ctx, layout_.pipelineLayout, shader)) {}

void ScreenPass::record(const FrameContext& fc, uint32_t mode) const {
  recordOver(fc, mode, glm::uvec4(0, 0, fc.targets.width, fc.targets.height), 1);
}

void ScreenPass::recordOver(const FrameContext& fc, uint32_t mode, const glm::uvec4& rect, uint32_t stride) const {
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  gpu::DrawPush push{};
  push.objectMaterial = glm::uvec4(mode, rect.x, rect.y, stride);
  layout_.push(fc, push);
  const uint32_t w = (rect.z - rect.x + stride - 1) / stride, h = (rect.w - rect.y + stride - 1) / stride;
  vkCmdDispatch(fc.cmd, vk::groupsFor(w, RB_TILE_SIZE), vk::groupsFor(h, RB_TILE_SIZE), 1);
}

}  // namespace raybudget::passes
