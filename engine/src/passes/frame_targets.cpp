#include "passes/frame_targets.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "raybudget/error.h"
#include "raybudget/image_io.h"
#include "shared/config.h"

namespace raybudget::passes {
namespace {

vk::Image image2d(const vk::Context& ctx, VkFormat format, uint32_t w, uint32_t h, VkImageUsageFlags usage, uint32_t layers = 1,
                  bool cube = false, uint32_t mips = 1) {
  vk::ImageDesc d;
  d.format = format;
  d.width = w;
  d.height = h;
  d.layers = layers;
  d.cube = cube;
  d.mips = mips;
  d.usage = usage;
  return vk::createImage(ctx, d);
}

}  // namespace

FrameTargets createFrameTargets(const vk::Context& ctx, uint32_t width, uint32_t height, const ShadowViews& shadows,
                                uint32_t shadowMapSize, const std::string& environmentMap, uint32_t lightCount, uint32_t probeCount,
                                const TargetNeeds& needs) {
  FrameTargets t;
  t.width = width;
  t.height = height;
  t.needs = needs;
  const VkImageUsageFlags attach = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  const VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  t.depth = image2d(ctx, kDepthFormat, width, height,
                    VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  t.normal = image2d(ctx, kNormalFormat, width, height, attach | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  t.baseMetal = image2d(ctx, kBaseMetalFormat, width, height, attach | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  t.roughTransIor = image2d(ctx, kRoughTransIorFormat, width, height, attach | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  t.emissive = image2d(ctx, kEmissiveFormat, width, height, attach | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  t.objectId = image2d(ctx, kIdFormat, width, height, attach | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  t.materialId = image2d(ctx, kIdFormat, width, height, attach | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  // Full-precision world position (+ packed geometric normal): secondary rays start at the
  // exact surface point, which depth reconstruction cannot give to within a few ulps.
  t.position = image2d(ctx, kPositionFormat, width, height, attach | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  // Clearcoat, sheen and specular per pixel (gbuffer.glsl's readLayers; zero: none).
  t.layers = image2d(ctx, kLayersFormat, needs.layers ? width : 1, needs.layers ? height : 1, attach | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  {
    vk::ImageDesc d;
    d.format = kLayersFormat;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    t.noLayers = vk::createImage(ctx, d);
    vk::uploadTexture(ctx, t.noLayers, std::vector<uint8_t>(16, 0));
  }
  t.direct = image2d(ctx, kHdrFormat, width, height, storage);
  t.reflection = image2d(ctx, kHdrFormat, width, height, storage);
  t.refraction = image2d(ctx, kHdrFormat, width, height, storage);
  t.hdr = image2d(ctx, kHdrFormat, width, height, storage | VK_IMAGE_USAGE_SAMPLED_BIT);  // sampled: the next frame's reflections
  const uint32_t ssrW = needs.screenReflections ? width : 1, ssrH = needs.screenReflections ? height : 1;
  t.ssr = image2d(ctx, kHdrFormat, ssrW, ssrH, storage);
  // The pyramid's levels 1.. (level 0 is the G-buffer's depth): mip m holds level m + 1.
  const uint32_t levels = std::min<uint32_t>(uint32_t(std::floor(std::log2(double(std::max(ssrW, ssrH))))) + 1, RB_HIZ_LEVELS);
  const uint32_t pyramidMips = std::max(levels, 2u) - 1;
  t.depthPyramid = image2d(ctx, VK_FORMAT_R32_SFLOAT, std::max(ssrW / 2, 1u), std::max(ssrH / 2, 1u),
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, 1, false, pyramidMips);
  for (uint32_t l = 0; l < pyramidMips; ++l) t.depthPyramidLevels.push_back(vk::createView(ctx, t.depthPyramid, VK_IMAGE_VIEW_TYPE_2D, l, 1, 0, 1));
  t.ldr = image2d(ctx, kLdrFormat, width, height, storage);
  const uint32_t maskLayers = 2 * std::max(lightCount, 1u);
  t.shadowMask = image2d(ctx, VK_FORMAT_R32_SFLOAT, width, height, storage, maskLayers);
  t.shadowMaskArray = vk::createView(ctx, t.shadowMask, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, 1, 0, maskLayers);
  t.tracedMask = image2d(ctx, VK_FORMAT_R32_UINT, width, height, storage | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  // Colour and geometry, per frame parity (include/fill_history.glsl).
  t.fillHistory = image2d(ctx, VK_FORMAT_R32G32B32A32_UINT, needs.fillHistory ? width : 1, needs.fillHistory ? height : 1,
                          VK_IMAGE_USAGE_STORAGE_BIT, RB_FILL_HISTORY_LAYERS);
  // Shadow-map corrections and geometry, per frame parity (include/shadow_history.glsl).
  t.shadowHistory = image2d(ctx, VK_FORMAT_R32G32B32A32_UINT, needs.shadowHistory ? width : 1, needs.shadowHistory ? height : 1,
                            VK_IMAGE_USAGE_STORAGE_BIT, RB_SHADOW_HISTORY_LAYERS);
  // Half the frame's resolution: glass shows it refracted and blurred.
  const uint32_t behindW = needs.behindGlass ? (width + 1) / 2 : 1, behindH = needs.behindGlass ? (height + 1) / 2 : 1;
  const uint32_t behindMips = uint32_t(std::floor(std::log2(double(std::max(behindW, behindH))))) + 1;
  t.behindGlass = image2d(ctx, kHdrFormat, behindW, behindH, storage | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 1, false,
                          behindMips);
  t.behindGlassMip0 = vk::createView(ctx, t.behindGlass, VK_IMAGE_VIEW_TYPE_2D, 0, 1, 0, 1);

  // Shadow maps: at least one layer / one cube, so the descriptors always have an image.
  const VkImageUsageFlags depthUsage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  t.shadowMapSize = shadowMapSize;
  t.cubeSize = std::max(shadowMapSize / 2, 16u);
  const uint32_t mapLayers = std::max(shadows.mapLayers, 1u);
  const uint32_t mapSize = shadows.mapLayers > 0 ? t.shadowMapSize : 1;
  t.shadowMaps = image2d(ctx, kDepthFormat, mapSize, mapSize, depthUsage, mapLayers);
  if (mapLayers == 1) {
    // A one-layer image's default view is 2D; the shader samples a 2D array.
    t.shadowMaps.view = vk::createView(ctx, t.shadowMaps, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, 1, 0, 1);
  }
  for (uint32_t l = 0; l < shadows.mapLayers; ++l)
    t.shadowMapLayers.push_back(vk::createView(ctx, t.shadowMaps, VK_IMAGE_VIEW_TYPE_2D, 0, 1, l, 1));
  const uint32_t cubes = std::max(shadows.pointCubes, 1u);
  // Sampled as a 2D array (face = layer) with the faces addressed in the shader: a cube
  // sized from its screen coverage uses only a corner of each face.
  const uint32_t faceSize = shadows.pointCubes > 0 ? t.cubeSize : 1;
  t.pointShadows = image2d(ctx, kDepthFormat, faceSize, faceSize, depthUsage, 6 * cubes);
  for (uint32_t f = 0; f < 6 * shadows.pointCubes; ++f)
    t.pointShadowFaces.push_back(vk::createView(ctx, t.pointShadows, VK_IMAGE_VIEW_TYPE_2D, 0, 1, f, 1));

  // Environment: the sky with a blitted mip chain, and the GGX-prefiltered copy.
  t.sky = image2d(ctx, kHdrFormat, RB_ENV_SIZE, RB_ENV_SIZE,
                  VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 6,
                  true, RB_ENV_MIPS);
  t.skyStorageView = vk::createView(ctx, t.sky, VK_IMAGE_VIEW_TYPE_CUBE, 0, 1, 0, 6);
  t.env = image2d(ctx, kHdrFormat, RB_ENV_SIZE, RB_ENV_SIZE, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, 6, true, RB_ENV_MIPS);
  for (uint32_t m = 0; m < RB_ENV_MIPS; ++m) t.envMipViews.push_back(vk::createView(ctx, t.env, VK_IMAGE_VIEW_TYPE_CUBE, m, 1, 0, 6));

  // Reflection probes.
  const uint32_t probeLayers = 6 * std::max(probeCount, 1u);
  t.probeRadiance = image2d(ctx, kHdrFormat, RB_ENV_SIZE, RB_ENV_SIZE,
                            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                            probeLayers, true, RB_PROBE_RADIANCE_MIPS);
  t.probeRadiance.view = vk::createView(ctx, t.probeRadiance, VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, 0, RB_PROBE_RADIANCE_MIPS, 0, probeLayers);
  t.probeRadianceMip0 = vk::createView(ctx, t.probeRadiance, VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, 0, 1, 0, probeLayers);
  t.reflectionProbes = image2d(ctx, kHdrFormat, RB_ENV_SIZE, RB_ENV_SIZE, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, probeLayers,
                               true, RB_ENV_MIPS);
  t.reflectionProbes.view = vk::createView(ctx, t.reflectionProbes, VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, 0, RB_ENV_MIPS, 0, probeLayers);
  for (uint32_t m = 0; m < RB_ENV_MIPS; ++m)
    t.reflectionProbeMips.push_back(vk::createView(ctx, t.reflectionProbes, VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, m, 1, 0, probeLayers));

  // The HDR environment image as half floats (1x1 black when the procedural sky is used).
  uint32_t ew = 1, eh = 1;
  std::vector<float> texels(4, 0.0f);
  if (!environmentMap.empty()) {
    texels = readExr(environmentMap, ew, eh);
    for (float v : texels)
      if (!std::isfinite(v)) throw Error(environmentMap + ": the environment image holds NaN or Inf texels");
    t.hasEnvSource = true;
  }
  std::vector<uint8_t> halfs(texels.size() * 2);
  for (size_t i = 0; i < texels.size(); ++i) {
    const uint16_t h = uint16_t(glm::packHalf1x16(std::min(texels[i], 65504.0f)));
    std::memcpy(halfs.data() + i * 2, &h, 2);
  }
  vk::ImageDesc d;
  d.format = kHdrFormat;
  d.width = ew;
  d.height = eh;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  t.envSource = vk::createImage(ctx, d);
  vk::uploadTexture(ctx, t.envSource, halfs);
  return t;
}

}  // namespace raybudget::passes
