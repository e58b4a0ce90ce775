// Every image the frame renders into: the G-buffer, the shadow maps, the environment maps
// and the compute outputs, with the per-layer / per-mip views the passes need.
#pragma once
#include <vector>

#include "passes/scene_gpu.h"
#include "raybudget/core.h"
#include "shared/config.h"
#include "vk/pipelines.h"
#include "vk/resources.h"

namespace raybudget::passes {

inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kBaseMetalFormat = VK_FORMAT_R8G8B8A8_UNORM;
inline constexpr VkFormat kRoughTransIorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kEmissiveFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;
inline constexpr VkFormat kPositionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kLayersFormat = VK_FORMAT_R32G32B32A32_UINT;
inline constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kLdrFormat = VK_FORMAT_R8G8B8A8_UNORM;

// The fallbacks' images a scene and its settings can use; the others are made 1x1, bound but
// never read (their passes never run).
struct TargetNeeds {
  bool behindGlass = true;            // screen-space transmission: glass in the scene, the fallback on
  bool screenReflections = true;      // a surface smooth enough for screen-space reflections, the fallback on
  bool fillHistory = false;           // reduced ray rates for reflections or refractions: their fill (shaders/include/fill_history.glsl)
  bool shadowHistory = false;         // reduced ray rates for shadows: their fill (shaders/include/shadow_history.glsl)
  bool layers = true;                 // a material with layers: the G-buffer's layers target is drawn (else read nowhere)
};

struct FrameTargets {
  uint32_t width = 0, height = 0;
  // 8x8 tiles covering the frame (the tile list, the per-tile passes).
  uint32_t tileCount() const { return vk::groupsFor(width, RB_TILE_SIZE) * vk::groupsFor(height, RB_TILE_SIZE); }
  // G-buffer (color attachments in this order, then depth).
  vk::Image depth, normal, baseMetal, roughTransIor, emissive, objectId, materialId, position, layers;
  vk::Image noLayers;  // 1x1, bound where a host's G-buffer has no layers
  // Compute outputs, kept in GENERAL layout.
  vk::Image direct, reflection, refraction, hdr, ldr;
  vk::Image fillHistory;  // the reflection and refraction fill's history: RB_FILL_HISTORY_LAYERS layers (1x1 when not needed)
  vk::Image shadowHistory;  // the shadow fill's history: RB_SHADOW_HISTORY_LAYERS layers (1x1 when not needed)
  TargetNeeds needs;      // what the images were made for (the others are 1x1)
  // Raster fallbacks.
  vk::Image shadowMaps;                            // 2D array, one layer per directional/spot light
  std::vector<vk::Owned<VkImageView>> shadowMapLayers;
  vk::Image pointShadows;                          // 2D array, 6 layers (cube faces) per point light
  std::vector<vk::Owned<VkImageView>> pointShadowFaces;
  vk::Image sky, env;                              // cube maps with RB_ENV_MIPS mips
  vk::Owned<VkImageView> skyStorageView;           // mip 0
  std::vector<vk::Owned<VkImageView>> envMipViews;  // one cube view per mip
  vk::Image envSource;                             // equirectangular HDR image, or 1x1 black
  // Ray-traced light visibility, a layer per light, then a layer per light of the shadow
  // map's visibility where a reduced ray rate traced (the lighting pass's fill reads both).
  vk::Image shadowMask;
  vk::Owned<VkImageView> shadowMaskArray;          // 2D-array view (also for one light)
  vk::Image tracedMask;                            // R32_UINT: the RB_RT_* effects traced per pixel
  vk::Image behindGlass;                           // the opaque frame behind transmissive surfaces, half resolution, full mip chain
  vk::Owned<VkImageView> behindGlassMip0;          // its mip 0, written by behind_glass.comp
  // Reflection probes, cube arrays of 6 layers per probe: the captured radiance with a full
  // mip chain (its mip 0 written by probe_capture.comp), and its GGX-prefiltered copy.
  vk::Image probeRadiance;
  vk::Owned<VkImageView> probeRadianceMip0;
  vk::Image reflectionProbes;
  std::vector<vk::Owned<VkImageView>> reflectionProbeMips;  // one cube-array view per mip
  // Screen-space reflections: the min-depth pyramid (R32F, a mip per level, each with a
  // storage view) and their result (RGBA16F).
  vk::Image depthPyramid;
  std::vector<vk::Owned<VkImageView>> depthPyramidLevels;
  vk::Image ssr;
  bool hasEnvSource = false;
  uint32_t shadowMapSize = 0, cubeSize = 0;

  // The G-buffer as the passes read it: these images, or a host's (Renderer::recordFrame).
  core::GBuffer gbufferViews() const {
    return {depth.view, normal.view, baseMetal.view, roughTransIor.view, emissive.view, objectId.view, materialId.view, position.view,
            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, layers.view};
  }

  std::vector<const vk::Image*> gbufferColors() const {
    return {&normal, &baseMetal, &roughTransIor, &emissive, &objectId, &materialId, &position, &layers};
  }
};

// `environmentMap`: an equirectangular OpenEXR path, or empty for the procedural sky.
// `probeCount`: reflection probes (at least one cube array layer set is made). Shadow maps are
// made at `shadowMapSize` for the lights that have them (1x1 where none does).
FrameTargets createFrameTargets(const vk::Context& ctx, uint32_t width, uint32_t height, const ShadowViews& shadows,
                                uint32_t shadowMapSize, const std::string& environmentMap, uint32_t lightCount, uint32_t probeCount,
                                const TargetNeeds& needs);

}  // namespace raybudget::passes
