// Raster fallback for shadows: one depth map per directional/spot light and a depth cube
// per point light, sampled with PCF by the lighting. Lights are static and their views fixed
// at load, so a view is rendered once and again only when a caster inside it moves or its
// size changes. A spot or point light's map is sized from its screen coverage: it uses the
// first N x N texels of its layers (N a power of two, at most the allocated size), N about
// the pixels its reach spans on screen, so a far or off-screen light renders few texels.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::passes {

class ShadowMapPass {
 public:
  // `slopeBias`: RenderSettings::shadowSlopeBias.
  ShadowMapPass(const vk::Context& ctx, PassLayouts& layouts, const ShadowViews& views, const FrameTargets& targets, float slopeBias);
  // False when the scene has no light with a shadow map (nothing recorded).
  static bool needed(const SceneGpu& scene) { return scene.shadows.mapLayers + scene.shadows.pointCubes > 0; }
  // Marks the views that see an object's bounding sphere before or after it moved.
  void objectMoved(const ShadowViews& views, const glm::vec4& before, const glm::vec4& after);
  // Sizes each spot and point light's map for the camera (`focalPixels`: the projection's
  // focal length in pixels); a map whose size changes is rendered again. Hysteresis: a map
  // grows as soon as it is too small, and shrinks (to twice what it needs) only once a quarter
  // of its side would do, so a camera moving to and fro does not render it again each frame.
  void fit(const ShadowViews& views, const glm::mat4& cameraViewProj, const glm::vec3& eye, float focalPixels);
  // The side in texels a view (layer, then cube) uses.
  uint32_t viewSize(uint32_t view) const { return size_[view]; }
  bool anyStale() const;
  struct Recorded {
    uint32_t views = 0;
    uint32_t draws = 0;
    uint32_t texels = 0;
  };
  // Renders the stale views only; what it recorded.
  Recorded record(const FrameContext& fc);
  // Before the first frame: every layer into SHADER_READ_ONLY, so unused ones are valid.
  static void initialize(VkCommandBuffer cmd, const FrameTargets& t);
  // The power-of-two side a light's map needs to show `reach` (w < 0: everywhere) with about
  // a texel per pixel, within [kMinSize, full]; kMinSize when the reach is off screen.
  static uint32_t neededSize(const glm::vec4& reach, uint32_t full, const glm::mat4& cameraViewProj, const glm::vec3& eye, float focalPixels);
  static constexpr uint32_t kMinSize = 64;

 private:
  uint32_t renderView(const FrameContext& fc, VkImageView view, uint32_t size, const glm::mat4& viewProj) const;
  // The sized lights' share of the layer and texel size, into the light buffer.
  void recordLightUpdates(const FrameContext& fc);
  const PassLayout& layout_;
  std::vector<bool> stale_;     // per map layer, then per cube face
  std::vector<uint32_t> size_;  // per layer, then per cube: the side it uses
  std::vector<uint32_t> full_;  // per layer, then per cube: the side it has
  std::vector<bool> resized_;   // per layer, then per cube: its light's record is out of date
  float slopeBias_;             // RenderSettings::shadowSlopeBias
  bool fitted_ = false;         // the first fit takes the needed sizes as they are
  vk::Owned<VkPipeline> opaque_;  // depth only
  vk::Owned<VkPipeline> masked_;  // alpha-tested fragment stage
};

}  // namespace raybudget::passes
