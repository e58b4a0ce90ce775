// Descriptor set layouts, pipeline layouts and pools, owned; and a self-contained descriptor
// set for a family of compute pipelines: bindings 0..n-1 of the given types, one
// push-constant range, the pipeline layout and a one-set pool.
#pragma once
#include <span>

#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::vk {

Owned<VkDescriptorSetLayout> createSetLayout(const Context& ctx, std::span<const VkDescriptorSetLayoutBinding> bindings);
// One set layout and `pushBytes` of push constants for `stages` (none when 0).
Owned<VkPipelineLayout> createPipelineLayout(const Context& ctx, VkDescriptorSetLayout setLayout, VkShaderStageFlags stages, uint32_t pushBytes);
Owned<VkDescriptorPool> createPool(const Context& ctx, std::span<const VkDescriptorPoolSize> sizes, uint32_t maxSets,
                                   VkDescriptorPoolCreateFlags flags = 0);

struct ComputeSet {
  Owned<VkDescriptorSetLayout> setLayout;
  Owned<VkPipelineLayout> pipelineLayout;
  Owned<VkDescriptorPool> pool;
  VkDescriptorSet set = VK_NULL_HANDLE;  // freed with the pool
};

ComputeSet createComputeSet(const Context& ctx, std::span<const VkDescriptorType> types, uint32_t pushBytes);

// Points storage-buffer binding i of `set` at buffers[i] (whole buffers).
void writeStorageBuffers(const Context& ctx, VkDescriptorSet set, std::span<const VkBuffer> buffers);

}  // namespace raybudget::vk
