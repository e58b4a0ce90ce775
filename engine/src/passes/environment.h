// Raster fallback for reflections and refractions: the procedural sky rendered into a cube
// map and GGX-prefiltered into RB_ENV_MIPS roughness levels. Static, so it runs once.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::passes {

// The bound prefilter pipeline (env_prefilter.comp, probe_prefilter.comp) over every
// roughness level of RB_ENV_MIPS, one dispatch each: push x the level, y `probe` (the
// reflection probe; unused for the sky).
void recordPrefilterLevels(const FrameContext& fc, const PassLayout& layout, uint32_t probe, uint32_t first = 0, uint32_t count = RB_ENV_MIPS);

class EnvironmentPass {
 public:
  EnvironmentPass(const vk::Context& ctx, PassLayouts& layouts);
  void record(const FrameContext& fc) const;

 private:
  const PassLayout& layout_;
  vk::Owned<VkPipeline> sky_;
  vk::Owned<VkPipeline> prefilter_;
};

}  // namespace raybudget::passes
