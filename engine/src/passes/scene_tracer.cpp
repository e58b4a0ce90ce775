#include "passes/scene_tracer.h"

#include <algorithm>
#include <vector>

namespace raybudget::passes {

std::unique_ptr<SceneTracer> createSceneTracer(const vk::Context& ctx, const Scene& scene, const RenderSettings& settings) {
  if (settings.rayTracing.tracer == Tracer::Native) return createNativeTracer(ctx, scene);  // throws where the device has none
  return createComputeTracer(ctx, scene, settings.rayTracing.spatialSplits);
}

void updateBindingsAmong(VkDevice device, std::span<const VkWriteDescriptorSet> writes, std::span<const uint32_t> only) {
  std::vector<VkWriteDescriptorSet> wanted;
  for (const VkWriteDescriptorSet& w : writes)
    if (std::binary_search(only.begin(), only.end(), w.dstBinding)) wanted.push_back(w);
  vkUpdateDescriptorSets(device, uint32_t(wanted.size()), wanted.data(), 0, nullptr);
}

uint8_t* stagingOf(const vk::Context& ctx, vk::Buffer& staging, VkDeviceSize bytes) {
  if (staging.size < bytes) staging = vk::createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
  return static_cast<uint8_t*>(staging.mapped);
}

}  // namespace raybudget::passes
