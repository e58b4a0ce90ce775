#include "passes/reflection_probes.h"

#include <algorithm>

#include "passes/environment.h"
#include "passes/frame_targets.h"
#include "probe_prefilter_comp.h"
#include "shared/config.h"
#include "vk/pipelines.h"

namespace raybudget::passes {
namespace {

static_assert((RB_ENV_SIZE >> (RB_PROBE_RADIANCE_MIPS - 1)) == 1, "the captured radiance's last mip is 1x1");
static_assert(kMaxReflectionProbes == RB_MAX_PROBES);

bool sphereMeetsBox(const glm::vec4& sphere, const ReflectionProbe& p) {
  const glm::vec3 c(sphere);
  const glm::vec3 nearest = glm::clamp(c, p.boxMin, p.boxMax);
  const glm::vec3 d = c - nearest;
  return glm::dot(d, d) <= sphere.w * sphere.w;
}

}  // namespace

ReflectionProbePass::ReflectionProbePass(const vk::Context& ctx, PassLayouts& layouts, std::vector<ReflectionProbe> probes, vk::Spirv capture)
    : ctx_(ctx),
      layout_(layouts.create({capture, kSpirv_probe_prefilter_comp})),
      captureShader_(capture),
      probes_(std::move(probes)),
      pending_(probes_.size(), kWhole) {}

void ReflectionProbePass::objectMoved(const glm::vec4& before, const glm::vec4& after) {
  // A recapture under way starts again: its faces so far may show the object where it was.
  for (size_t i = 0; i < probes_.size(); ++i)
    if ((sphereMeetsBox(before, probes_[i]) || sphereMeetsBox(after, probes_[i])) && pending_[i] != kWhole) pending_[i] = 0;
}

bool ReflectionProbePass::anyStale() const {
  return std::any_of(pending_.begin(), pending_.end(), [](int p) { return p != kCurrent; });
}

void ReflectionProbePass::writeUniforms(gpu::FrameUniforms& u, bool use) const {
  u.probes = glm::uvec4(use ? uint32_t(probes_.size()) : 0u, 0u, 0u, 0u);
  for (size_t i = 0; i < probes_.size(); ++i) {
    u.probeCenter[i] = glm::vec4(probes_[i].center, 1.0f);
    u.probeBoxMin[i] = glm::vec4(probes_[i].boxMin, 0.0f);
    u.probeBoxMax[i] = glm::vec4(probes_[i].boxMax, 0.0f);
  }
}

void ReflectionProbePass::initialize(VkCommandBuffer cmd, const FrameTargets& t) {
  for (const vk::Image* img : {&t.probeRadiance, &t.reflectionProbes})
    vk::imageBarrier(cmd, *img, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                     VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

uint32_t ReflectionProbePass::record(const FrameContext& fc) {
  if (!capture_) {
    capture_ = vk::createComputePipeline(ctx_, layout_.pipelineLayout, captureShader_);
    prefilter_ = vk::createComputePipeline(ctx_, layout_.pipelineLayout, kSpirv_probe_prefilter_comp);
  }
  const FrameTargets& t = fc.targets;
  const uint32_t groups = vk::groupsFor(RB_ENV_SIZE, RB_TILE_SIZE);
  constexpr VkPipelineStageFlags2 compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  // What each probe does this frame: capture (whole, or its next face) and prefilter (every
  // level, or its next one).
  struct Step {
    uint32_t probe;
    int face = -1;        // -1: none; 6: all
    int level = -1;       // -1: none; RB_ENV_MIPS: all
  };
  std::vector<Step> steps;
  uint32_t completed = 0;
  bool mips = false;
  for (uint32_t p = 0; p < probes_.size(); ++p) {
    int& s = pending_[p];
    if (s == kCurrent) continue;
    Step step{p};
    if (s == kWhole) {
      step = {p, 6, RB_ENV_MIPS};
      s = kCurrent;
    } else if (s < kFirstLevel) {  // a face of a recapture; the sixth brings the mip chain
      step.face = s++;
    } else {
      step.level = s - kFirstLevel;
      s = s + 1 == kFirstLevel + RB_ENV_MIPS ? kCurrent : s + 1;
    }
    mips = mips || step.face == 6 || step.face == 5;
    completed += s == kCurrent;
    steps.push_back(step);
  }
  const bool capturing = std::any_of(steps.begin(), steps.end(), [](const Step& s) { return s.face >= 0; });
  const bool prefiltering = std::any_of(steps.begin(), steps.end(), [](const Step& s) { return s.level >= 0; });

  // The image from its readers (keeping what it holds) to `pipeline`'s storage writes.
  auto writeWith = [&](const vk::Image& image, VkPipeline pipeline) {
    vk::imageBarrier(fc.cmd, image, compute, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    layout_.bind(fc, VK_PIPELINE_BIND_POINT_COMPUTE);
  };

  // 1. Radiance into mip 0 (the other layers keep theirs); a blitted mip chain down to 1x1
  // once a probe's faces are all in.
  if (capturing) {
    writeWith(t.probeRadiance, capture_);
    for (const Step& s : steps) {
      if (s.face < 0) continue;
      gpu::DrawPush push{};
      push.objectMaterial = glm::uvec4(s.probe, s.face == 6 ? 0u : uint32_t(s.face), 0u, 0u);
      layout_.push(fc, push);
      vkCmdDispatch(fc.cmd, groups, groups, s.face == 6 ? 6 : 1);
    }
    if (mips) {
      vk::imageBarrier(fc.cmd, t.probeRadiance, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
      vk::generateMips(fc.cmd, t.probeRadiance);
    } else {
      vk::imageBarrier(fc.cmd, t.probeRadiance, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, compute, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                       VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
  }

  // 2. GGX prefilter, one dispatch per probe and roughness level.
  if (prefiltering) {
    writeWith(t.reflectionProbes, prefilter_);
    for (const Step& s : steps) {
      if (s.level == RB_ENV_MIPS) recordPrefilterLevels(fc, layout_, s.probe);
      else if (s.level >= 0) recordPrefilterLevels(fc, layout_, s.probe, uint32_t(s.level), 1);
    }
    vk::imageBarrier(fc.cmd, t.reflectionProbes, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, compute | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  }
  return completed;
}

}  // namespace raybudget::passes
