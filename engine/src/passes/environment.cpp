#include "passes/environment.h"

#include "env_prefilter_comp.h"
#include "shared/config.h"
#include "shared/types.h"
#include "sky_comp.h"
#include "vk/pipelines.h"

namespace raybudget::passes {

void recordPrefilterLevels(const FrameContext& fc, const PassLayout& layout, uint32_t probe, uint32_t first, uint32_t count) {
  for (uint32_t mip = first; mip < first + count; ++mip) {
    gpu::DrawPush push{};
    push.objectMaterial = glm::uvec4(mip, probe, 0u, 0u);
    layout.push(fc, push);
    const uint32_t g = vk::groupsFor(std::max(RB_ENV_SIZE >> mip, 1), RB_TILE_SIZE);
    vkCmdDispatch(fc.cmd, g, g, 6);
  }
}

EnvironmentPass::EnvironmentPass(const vk::Context& ctx, PassLayouts& layouts)
    : layout_(layouts.create({kSpirv_sky_comp, kSpirv_env_prefilter_comp})),
      sky_(vk::createComputePipeline(ctx, layout_.pipelineLayout, kSpirv_sky_comp)),
      prefilter_(vk::createComputePipeline(ctx, layout_.pipelineLayout, kSpirv_env_prefilter_comp)) {}

void EnvironmentPass::record(const FrameContext& fc) const {
  const FrameTargets& t = fc.targets;
  const uint32_t groups = vk::groupsFor(RB_ENV_SIZE, RB_TILE_SIZE);
  // 1. Sky radiance into mip 0, then a blitted mip chain for filtered sampling.
  vk::imageBarrier(fc.cmd, t.sky, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, sky_);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  gpu::DrawPush skyPush{};
  skyPush.objectMaterial.x = t.hasEnvSource ? 1u : 0u;
  layout_.push(fc, skyPush);
  vkCmdDispatch(fc.cmd, groups, groups, 6);
  vk::imageBarrier(fc.cmd, t.sky, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  vk::generateMips(fc.cmd, t.sky);

  // 2. GGX prefilter, one dispatch per roughness level.
  vk::imageBarrier(fc.cmd, t.env, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, prefilter_);
  recordPrefilterLevels(fc, layout_, 0);
  vk::imageBarrier(fc.cmd, t.env, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

}  // namespace raybudget::passes
