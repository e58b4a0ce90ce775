#include "passes/trace_pass.h"

#include <cstddef>

#include "shared/config.h"

namespace raybudget::passes {
namespace {

vk::Owned<VkPipeline> tracePipeline(const vk::Context& ctx, VkPipelineLayout layout, vk::Spirv shader, bool fill, uint32_t paths) {
  struct Constants {
    VkBool32 fill;
    uint32_t paths;
  } values{fill ? VK_TRUE : VK_FALSE, paths};
  const VkSpecializationMapEntry entries[] = {{RB_FILL_CONSTANT_ID, offsetof(Constants, fill), sizeof(VkBool32)},
                                              {RB_PATHS_CONSTANT_ID, offsetof(Constants, paths), sizeof(uint32_t)}};
  // The shadow pass has no paths constant (0).
  const VkSpecializationInfo info{paths != 0 ? 2u : 1u, entries, sizeof(values), &values};
  return vk::createComputePipeline(ctx, layout, shader, &info);
}

}  // namespace

TracePass::TracePass(const vk::Context& ctx, PassLayouts& layouts, vk::Spirv shader, TileList tiles, uint32_t paths)
    : ctx_(ctx), layout_(layouts.create({shader})), shader_(shader), tiles_(tiles), paths_(paths) {}

void TracePass::recordOverTiles(const FrameContext& fc, bool fill) {
  if (!fill && !plain_) plain_ = tracePipeline(ctx_, layout_.pipelineLayout, shader_, false, paths_);
  if (fill && !filling_) filling_ = tracePipeline(ctx_, layout_.pipelineLayout, shader_, true, paths_);
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, fill ? filling_ : plain_);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  // Each list's header is a uvec4 whose xyz is its dispatch.
  vkCmdDispatchIndirect(fc.cmd, fc.selection.tileList.buffer, 16 * VkDeviceSize(tiles_));
}

}  // namespace raybudget::passes
