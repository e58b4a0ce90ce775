// Raster fallback for shadows: one depth map per directional/spot light and a depth cube
// per point light, rendered from the scene each frame; sampled with PCF by the lighting.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::passes {

class ShadowMapPass {
 public:
  ShadowMapPass(const vk::Context& ctx, PassLayouts& layouts);
  // False when the scene has no light with a shadow map (nothing recorded).
  static bool needed(const SceneGpu& scene) { return scene.shadows.mapLayers + scene.shadows.pointCubes > 0; }
  void record(const FrameContext& fc) const;
  // Before the first frame: every layer into SHADER_READ_ONLY, so unused ones are valid.
  static void initialize(VkCommandBuffer cmd, const FrameTargets& t);

 private:
  void renderView(const FrameContext& fc, VkImageView view, uint32_t size, const glm::mat4& viewProj) const;
  const PassLayout& layout_;
  vk::Owned<VkPipeline> opaque_;  // depth only
  vk::Owned<VkPipeline> masked_;  // alpha-tested fragment stage
};

}  // namespace raybudget::passes
