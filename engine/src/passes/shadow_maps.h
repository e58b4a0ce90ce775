// Raster fallback for shadows: one depth map per directional/spot light and a depth cube
// per point light, sampled with PCF by the lighting. Lights are static and their views fixed
// at load, so a view is rendered once and again only when a caster inside it moves.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::passes {

class ShadowMapPass {
 public:
  ShadowMapPass(const vk::Context& ctx, PassLayouts& layouts, const ShadowViews& views);
  // False when the scene has no light with a shadow map (nothing recorded).
  static bool needed(const SceneGpu& scene) { return scene.shadows.mapLayers + scene.shadows.pointCubes > 0; }
  // Marks the views that see an object's bounding sphere before or after it moved.
  void objectMoved(const ShadowViews& views, const glm::vec4& before, const glm::vec4& after);
  bool anyStale() const;
  struct Recorded {
    uint32_t views = 0;
    uint32_t draws = 0;
  };
  // Renders the stale views only; what it recorded.
  Recorded record(const FrameContext& fc);
  // Before the first frame: every layer into SHADER_READ_ONLY, so unused ones are valid.
  static void initialize(VkCommandBuffer cmd, const FrameTargets& t);

 private:
  uint32_t renderView(const FrameContext& fc, VkImageView view, uint32_t size, const glm::mat4& viewProj) const;
  const PassLayout& layout_;
  std::vector<bool> stale_;  // per map layer, then per cube face
  vk::Owned<VkPipeline> opaque_;  // depth only
  vk::Owned<VkPipeline> masked_;  // alpha-tested fragment stage
};

}  // namespace raybudget::passes
