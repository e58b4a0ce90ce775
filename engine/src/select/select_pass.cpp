#include "select/select_pass.h"

#include "select_unbudgeted_comp.h"
#include "shared/config.h"
#include "shared/types.h"
#include "tile_list_comp.h"
#include "vk/pipelines.h"
#include "vk/resources.h"

namespace raybudget::select {

SelectPass::SelectPass(const vk::Context& ctx, passes::PassLayouts& layouts)
    : layout_(layouts.create({kSpirv_select_unbudgeted_comp, kSpirv_tile_list_comp})),
      select_(vk::createComputePipeline(ctx, layout_.pipelineLayout, kSpirv_select_unbudgeted_comp)),
      tiles_(vk::createComputePipeline(ctx, layout_.pipelineLayout, kSpirv_tile_list_comp)) {}

void SelectPass::record(const passes::FrameContext& fc, SelectMode mode, uint32_t rate) const {
  const VkCommandBuffer cmd = fc.cmd;
  // Every list: no tiles yet, x = 0 groups; the trace counts at 0.
  const uint32_t emptyHeader[kTileListListBytes / 4] = {0, 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0};
  vkCmdUpdateBuffer(cmd, fc.selection.tileList.buffer, 0, sizeof(emptyHeader), emptyHeader);
  const uint32_t objects = fc.selection.objects;
  gpu::DrawPush push{};
  push.objectMaterial = glm::uvec4(objects, uint32_t(mode), rate, 0);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  if (mode != SelectMode::Keep) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, select_);
    layout_.push(fc, push);
    vkCmdDispatch(cmd, vk::groupsFor(objects, RB_GROUP_SIZE), 1, 1);
  }
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, tiles_);
  vkCmdDispatch(cmd, vk::groupsFor(fc.selection.tiles, RB_GROUP_SIZE), 1, 1);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

}  // namespace raybudget::select
