#include "select/coverage_pass.h"

#include "coverage_comp.h"
#include "object_metrics_comp.h"
#include "select/selection_buffers.h"
#include "shared/config.h"
#include "shared/types.h"
#include "vk/pipelines.h"
#include "vk/resources.h"

namespace raybudget::select {

namespace {

// The coverage shader with its classifier specialized in or out (coverage.comp's kClassify).
vk::Owned<VkPipeline> coveragePipeline(const vk::Context& ctx, VkPipelineLayout layout, bool classify) {
  const VkBool32 value = classify ? VK_TRUE : VK_FALSE;
  const VkSpecializationMapEntry entry{0, 0, sizeof(value)};
  const VkSpecializationInfo info{1, &entry, sizeof(value), &value};
  return vk::createComputePipeline(ctx, layout, kSpirv_coverage_comp, &info);
}

}  // namespace

CoveragePass::CoveragePass(const vk::Context& ctx, passes::PassLayouts& layouts)
    : layout_(layouts.create({kSpirv_coverage_comp, kSpirv_object_metrics_comp})),
      coverage_(coveragePipeline(ctx, layout_.pipelineLayout, false)),
      classifying_(coveragePipeline(ctx, layout_.pipelineLayout, true)),
      metrics_(vk::createComputePipeline(ctx, layout_.pipelineLayout, kSpirv_object_metrics_comp)) {}

void CoveragePass::record(const passes::FrameContext& fc, bool classify, bool reuse) const {
  const VkCommandBuffer cmd = fc.cmd;
  if (!reuse) vkCmdFillBuffer(cmd, fc.selection.coverage.buffer, 0, VK_WHOLE_SIZE, 0);
  // The stage's clock (shaders/include/stage_clock.glsl): it begins here.
  vkCmdFillBuffer(cmd, fc.selection.tileList.buffer, kTileListListBytes, kTileListHeaderBytes - kTileListListBytes, 0);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  if (!reuse) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classify ? classifying_ : coverage_);
    vkCmdDispatch(cmd, vk::groupsFor(fc.selection.tiles, RB_GROUP_SIZE), 1, 1);  // one invocation per tile
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
  const uint32_t objects = fc.selection.objects;
  gpu::DrawPush push{};
  push.objectMaterial.x = objects;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, metrics_);
  layout_.push(fc, push);
  vkCmdDispatch(cmd, vk::groupsFor(objects, RB_GROUP_SIZE), 1, 1);
}

}  // namespace raybudget::select
