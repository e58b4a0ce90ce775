#include "passes/tile_list_pass.h"

#include "shared/config.h"

namespace raybudget::passes {
namespace {

vk::Owned<VkPipeline> tileListPipeline(const vk::Context& ctx, VkPipelineLayout layout, vk::Spirv shader, uint32_t paths) {
  const VkSpecializationMapEntry entry{RB_PATHS_CONSTANT_ID, 0, sizeof(uint32_t)};
  // Only the effects pass has a paths constant (0 for the others).
  const VkSpecializationInfo info{1u, &entry, sizeof(paths), &paths};
  return vk::createComputePipeline(ctx, layout, shader, paths != 0 ? &info : nullptr);
}

}  // namespace

TileListPass::TileListPass(const vk::Context& ctx, PassLayouts& layouts, vk::Spirv shader, TileList tiles, uint32_t paths)
    : ctx_(ctx), layout_(layouts.create({shader})), shader_(shader), tiles_(tiles), paths_(paths) {}

void TileListPass::recordOverTiles(const FrameContext& fc) {
  if (!pipeline_) pipeline_ = tileListPipeline(ctx_, layout_.pipelineLayout, shader_, paths_);
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  // The list's indirect dispatch: the xyz of the header's uvec4 that TileList names.
  vkCmdDispatchIndirect(fc.cmd, fc.selection.tileList.buffer, 16 * VkDeviceSize(tiles_));
}

}  // namespace raybudget::passes
