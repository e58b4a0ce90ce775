#include "passes/descriptors.h"

#include <algorithm>

#include "passes/bindings.h"
#include "shared/config.h"
#include "vk/check.h"

namespace raybudget::passes {
namespace {

struct BindingInfo {
  VkDescriptorType type;
  uint32_t count;
};

BindingInfo bindingInfo(uint32_t binding, uint32_t textureCount, bool native) {
  // The tracer's three bindings (rayquery.glsl): compute BVH texels and instances, or the
  // TLAS and the geometry table (the third binding then unused, kept for one layout shape).
  if (native && binding == kBvhNodes) return {VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1};
  if (native && (binding == kBvhTriangles || binding == kBvhInstances)) return {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  if (binding == kFrameUniforms) return {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1};
  if (binding == kLights) return {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1};
  if (binding <= kVertices) return {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  if (binding == kTextures) return {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textureCount};
  if (binding == kTextureTransforms) return {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  if (binding <= kSkyMap || binding == kEnvSource || binding == kGPosition || binding == kShadowMapDepths ||
      binding == kPointShadowDepths || binding == kBehindGlass || binding == kReflectionProbes || binding == kProbeRadiance ||
      binding == kDepthPyramid || binding == kPreviousFrame || binding == kGLayers)
    return {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  if (binding == kEnvStorage || binding == kReflectionProbeMips) return {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, RB_ENV_MIPS};
  if (binding == kDepthPyramidLevels) return {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, RB_HIZ_LEVELS};
  if (binding == kBvhNodes || binding == kBvhTriangles) return {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1};
  if (binding == kBvhInstances || binding == kIndices) return {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  if (binding >= kCoverage && binding <= kItemCosts) return {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  return {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1};
}

}  // namespace

std::pair<VkDescriptorType, uint32_t> bindingType(uint32_t binding, uint32_t textureCount, bool nativeTracer) {
  const BindingInfo info = bindingInfo(binding, textureCount, nativeTracer);
  return {info.type, info.count};
}

bool isGBufferBinding(uint32_t binding) {
  return (binding >= kGDepth && binding <= kGMaterialId) || binding == kGPosition || binding == kGLayers;
}

vk::DescriptorNeeds descriptorNeeds(uint32_t textureCount, bool nativeTracer) {
  vk::DescriptorNeeds n;
  for (uint32_t b = 0; b < kBindingCount; ++b) {
    const BindingInfo info = bindingInfo(b, textureCount, nativeTracer);
    switch (info.type) {
      case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: n.storageBuffers += info.count; break;
      case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: n.uniformBuffers += info.count; break;
      case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE: n.storageImages += info.count; break;
      case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER: n.sampledImages += info.count; break;  // counted as sampled images
      case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
        n.sampledImages += info.count;
        n.samplers += info.count;
        break;
      default: break;  // the acceleration structure has a limit of its own (at least 16)
    }
  }
  return n;
}

Samplers createSamplers(const vk::Context& ctx) {
  Samplers s;
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = ci.minFilter = VK_FILTER_NEAREST;
  ci.addressModeU = ci.addressModeV = ci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  s.nearest = vk::createSampler(ctx, ci);
  // Hardware PCF (bilinear compare) where the depth format can be filtered.
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), kDepthFormat, &fp);
  const bool linearDepth = fp.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  ci.magFilter = ci.minFilter = linearDepth ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  ci.compareEnable = VK_TRUE;
  ci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  s.shadow = vk::createSampler(ctx, ci);
  ci.compareEnable = VK_FALSE;
  ci.magFilter = ci.minFilter = VK_FILTER_LINEAR;
  ci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  ci.maxLod = VK_LOD_CLAMP_NONE;
  s.linear = vk::createSampler(ctx, ci);
  ci.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;  // longitude wraps around
  s.equirect = vk::createSampler(ctx, ci);
  return s;
}

void writeSet(const vk::Context& ctx, VkDescriptorSet set, std::span<const uint32_t> only, const vk::Buffer& uniforms, const SceneGpu& scene,
              const FrameTargets& t, const core::GBuffer& gbuffer, const select::SelectionBuffers& selection, const Samplers& samplers) {
  const core::GBuffer& gb = gbuffer;
  std::vector<VkDescriptorBufferInfo> buffers = {
      {uniforms.buffer, 0, VK_WHOLE_SIZE}, {scene.objects.buffer, 0, VK_WHOLE_SIZE}, {scene.materials.buffer, 0, VK_WHOLE_SIZE},
      {scene.lights.buffer, 0, VK_WHOLE_SIZE}, {scene.vertices.buffer, 0, VK_WHOLE_SIZE}};
  std::vector<VkDescriptorImageInfo> textures;
  for (const GpuTexture& tex : scene.textures)
    textures.push_back({tex.sampler, scene.textureImages[tex.image].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const VkDescriptorImageInfo sampled[] = {
      {samplers.nearest, gb.depth, gb.layout},         {samplers.nearest, gb.normal, gb.layout},   {samplers.nearest, gb.baseMetal, gb.layout},
      {samplers.nearest, gb.roughTransIor, gb.layout}, {samplers.nearest, gb.emissive, gb.layout}, {samplers.nearest, gb.objectId, gb.layout},
      {samplers.nearest, gb.materialId, gb.layout},    {samplers.shadow, t.shadowMaps.view, ro}, {samplers.shadow, t.pointShadows.view, ro},
      {samplers.linear, t.env.view, ro},             {samplers.linear, t.sky.view, ro}};
  const VkImageLayout g = VK_IMAGE_LAYOUT_GENERAL;
  const VkDescriptorImageInfo storage[] = {{VK_NULL_HANDLE, t.direct.view, g}, {VK_NULL_HANDLE, t.reflection.view, g},
                                           {VK_NULL_HANDLE, t.hdr.view, g},    {VK_NULL_HANDLE, t.ldr.view, g},
                                           {VK_NULL_HANDLE, t.skyStorageView, g}};
  // An array binding of per-mip storage views, `count` long: past the last view, the last one
  // again (never written there).
  auto storageViews = [&](const std::vector<vk::Owned<VkImageView>>& views, uint32_t count) {
    std::vector<VkDescriptorImageInfo> infos;
    for (uint32_t i = 0; i < count; ++i) infos.push_back({VK_NULL_HANDLE, views[std::min<size_t>(i, views.size() - 1)], g});
    return infos;
  };
  const std::vector<VkDescriptorImageInfo> envMips = storageViews(t.envMipViews, RB_ENV_MIPS);

  const bool native = scene.tracer->kind() == Tracer::Native;
  std::vector<VkWriteDescriptorSet> writes;
  auto write = [&](uint32_t binding, uint32_t count, const VkDescriptorBufferInfo* b, const VkDescriptorImageInfo* i,
                   const VkBufferView* texels = nullptr) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = binding;
    w.descriptorCount = count;
    w.descriptorType = bindingInfo(binding, count, native).type;
    w.pBufferInfo = b;
    w.pImageInfo = i;
    w.pTexelBufferView = texels;
    writes.push_back(w);
  };
  for (uint32_t b = kFrameUniforms; b <= kVertices; ++b) write(b, 1, &buffers[b], nullptr);
  write(kTextures, uint32_t(textures.size()), nullptr, textures.data());
  const VkDescriptorBufferInfo transforms{scene.textureTransforms.buffer, 0, VK_WHOLE_SIZE};
  write(kTextureTransforms, 1, &transforms, nullptr);
  for (uint32_t b = kGDepth; b <= kSkyMap; ++b) write(b, 1, nullptr, &sampled[b - kGDepth]);
  for (uint32_t b = kDirectImage; b <= kSkyStorage; ++b) write(b, 1, nullptr, &storage[b - kDirectImage]);
  write(kEnvStorage, uint32_t(envMips.size()), nullptr, envMips.data());
  const VkDescriptorImageInfo envSource{samplers.equirect, t.envSource.view, ro};
  write(kEnvSource, 1, nullptr, &envSource);
  const VkDescriptorBufferInfo indices{scene.indices.buffer, 0, VK_WHOLE_SIZE};
  write(kIndices, 1, &indices, nullptr);
  const VkDescriptorImageInfo mask{VK_NULL_HANDLE, t.shadowMaskArray, g};
  write(kShadowMask, 1, nullptr, &mask);
  const VkDescriptorImageInfo traced{VK_NULL_HANDLE, t.tracedMask.view, g};
  write(kTracedMask, 1, nullptr, &traced);
  const VkDescriptorImageInfo position{samplers.nearest, gb.position, gb.layout};
  write(kGPosition, 1, nullptr, &position);
  // A host G-buffer without material layers: a 1x1 image never read (frame.exposure.w is 0).
  const VkDescriptorImageInfo layers{samplers.nearest, gb.layers ? gb.layers : t.noLayers.view, gb.layers ? gb.layout : ro};
  write(kGLayers, 1, nullptr, &layers);
  const VkDescriptorImageInfo refraction{VK_NULL_HANDLE, t.refraction.view, g};
  write(kRefractionImage, 1, nullptr, &refraction);
  const VkDescriptorImageInfo history{VK_NULL_HANDLE, t.fillHistory.view, g};
  write(kFillHistory, 1, nullptr, &history);
  const VkDescriptorImageInfo shadowHistory{VK_NULL_HANDLE, t.shadowHistory.view, g};
  write(kShadowHistory, 1, nullptr, &shadowHistory);
  const VkDescriptorBufferInfo heuristic[] = {{selection.coverage.buffer, 0, VK_WHOLE_SIZE},
                                              {selection.objectParams.buffer, 0, VK_WHOLE_SIZE},
                                              {selection.objectRecords.buffer, 0, VK_WHOLE_SIZE},
                                              {selection.selection.buffer, 0, VK_WHOLE_SIZE},
                                              {selection.tileList.buffer, 0, VK_WHOLE_SIZE},
                                              {selection.objectCosts.buffer, 0, VK_WHOLE_SIZE},
                                              {selection.tileObjects.buffer, 0, VK_WHOLE_SIZE},
                                              {selection.itemCosts.buffer, 0, VK_WHOLE_SIZE}};
  for (uint32_t b = kCoverage; b <= kItemCosts; ++b) write(b, 1, &heuristic[b - kCoverage], nullptr);
  // The shadow maps again, read as depths (no compare): where shadow rays may end.
  const VkDescriptorImageInfo depths[] = {{samplers.nearest, t.shadowMaps.view, ro}, {samplers.nearest, t.pointShadows.view, ro}};
  write(kShadowMapDepths, 1, nullptr, &depths[0]);
  write(kPointShadowDepths, 1, nullptr, &depths[1]);
  const VkDescriptorImageInfo behind[] = {{samplers.linear, t.behindGlass.view, ro}, {VK_NULL_HANDLE, t.behindGlassMip0, g}};
  write(kBehindGlass, 1, nullptr, &behind[0]);
  write(kBehindGlassImage, 1, nullptr, &behind[1]);
  const VkDescriptorImageInfo probes[] = {{samplers.linear, t.reflectionProbes.view, ro}, {samplers.linear, t.probeRadiance.view, ro},
                                          {VK_NULL_HANDLE, t.probeRadianceMip0, g}};
  write(kReflectionProbes, 1, nullptr, &probes[0]);
  write(kProbeRadiance, 1, nullptr, &probes[1]);
  write(kProbeRadianceImage, 1, nullptr, &probes[2]);
  const std::vector<VkDescriptorImageInfo> probeMips = storageViews(t.reflectionProbeMips, RB_ENV_MIPS);
  write(kReflectionProbeMips, uint32_t(probeMips.size()), nullptr, probeMips.data());
  // The pyramid and the previous frame stay in GENERAL: written and read in the same frame.
  const VkDescriptorImageInfo ssr[] = {{samplers.nearest, t.depthPyramid.view, g}, {samplers.linear, t.hdr.view, g}, {VK_NULL_HANDLE, t.ssr.view, g}};
  write(kDepthPyramid, 1, nullptr, &ssr[0]);
  write(kPreviousFrame, 1, nullptr, &ssr[1]);
  write(kSsrImage, 1, nullptr, &ssr[2]);
  const std::vector<VkDescriptorImageInfo> levels = storageViews(t.depthPyramidLevels, RB_HIZ_LEVELS);
  write(kDepthPyramidLevels, uint32_t(levels.size()), nullptr, levels.data());
  // Only the set's own bindings: a pass's layout holds those its shaders use.
  std::erase_if(writes, [&](const VkWriteDescriptorSet& w) { return !std::binary_search(only.begin(), only.end(), w.dstBinding); });
  vkUpdateDescriptorSets(ctx.device(), uint32_t(writes.size()), writes.data(), 0, nullptr);
  scene.tracer->writeBindings(ctx.device(), set, only);  // kBvhNodes, kBvhTriangles, kBvhInstances
}

}  // namespace raybudget::passes
