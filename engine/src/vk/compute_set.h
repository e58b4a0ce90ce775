// A self-contained descriptor set for a family of compute pipelines: bindings 0..n-1 of
// the given types, one push-constant range, the pipeline layout and a one-set pool.
#pragma once
#include <span>

#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::vk {

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
