#include "passes/trace_pass.h"

#include "shared/config.h"

namespace raybudget::passes {
namespace {

vk::Owned<VkPipeline> tracePipeline(const vk::Context& ctx, VkPipelineLayout layout, vk::Spirv shader, bool fill) {
  const VkBool32 value = fill ? VK_TRUE : VK_FALSE;
  const VkSpecializationMapEntry entry{RB_FILL_CONSTANT_ID, 0, sizeof(value)};
  const VkSpecializationInfo info{1, &entry, sizeof(value), &value};
  return vk::createComputePipeline(ctx, layout, shader, &info);
}

}  // namespace

TracePass::TracePass(const vk::Context& ctx, PassLayouts& layouts, vk::Spirv shader, TileList tiles)
    : ctx_(ctx), layout_(layouts.create({shader})), shader_(shader), tiles_(tiles) {}

void TracePass::recordOverTiles(const FrameContext& fc, bool fill) {
  if (!fill && !plain_) plain_ = tracePipeline(ctx_, layout_.pipelineLayout, shader_, false);
  if (fill && !filling_) filling_ = tracePipeline(ctx_, layout_.pipelineLayout, shader_, true);
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, fill ? filling_ : plain_);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  // Each list's header is a uvec4 whose xyz is its dispatch.
  vkCmdDispatchIndirect(fc.cmd, fc.selection.tileList.buffer, 16 * VkDeviceSize(tiles_));
}

}  // namespace raybudget::passes
