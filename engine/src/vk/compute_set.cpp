#include "vk/compute_set.h"

#include <vector>

#include "vk/check.h"

namespace raybudget::vk {

Owned<VkDescriptorSetLayout> createSetLayout(const Context& ctx, std::span<const VkDescriptorSetLayoutBinding> bindings) {
  const VkDevice device = ctx.device();
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.bindingCount = uint32_t(bindings.size());
  ci.pBindings = bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorSetLayout(device, &ci, nullptr, &layout));
  return Owned<VkDescriptorSetLayout>(layout, [device](VkDescriptorSetLayout x) { vkDestroyDescriptorSetLayout(device, x, nullptr); });
}

Owned<VkPipelineLayout> createPipelineLayout(const Context& ctx, VkDescriptorSetLayout setLayout, VkShaderStageFlags stages, uint32_t pushBytes) {
  const VkDevice device = ctx.device();
  const VkPushConstantRange range{stages, 0, pushBytes};
  VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  ci.setLayoutCount = 1;
  ci.pSetLayouts = &setLayout;
  ci.pushConstantRangeCount = pushBytes > 0 ? 1 : 0;
  ci.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreatePipelineLayout(device, &ci, nullptr, &layout));
  return Owned<VkPipelineLayout>(layout, [device](VkPipelineLayout x) { vkDestroyPipelineLayout(device, x, nullptr); });
}

Owned<VkDescriptorPool> createPool(const Context& ctx, std::span<const VkDescriptorPoolSize> sizes, uint32_t maxSets,
                                   VkDescriptorPoolCreateFlags flags) {
  const VkDevice device = ctx.device();
  VkDescriptorPoolCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  ci.flags = flags;
  ci.maxSets = maxSets;
  ci.poolSizeCount = uint32_t(sizes.size());
  ci.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(device, &ci, nullptr, &pool));
  return Owned<VkDescriptorPool>(pool, [device](VkDescriptorPool x) { vkDestroyDescriptorPool(device, x, nullptr); });
}

ComputeSet createComputeSet(const Context& ctx, std::span<const VkDescriptorType> types, uint32_t pushBytes) {
  ComputeSet c;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  std::vector<VkDescriptorPoolSize> sizes;
  for (uint32_t i = 0; i < types.size(); ++i) {
    bindings.push_back({i, types[i], 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    sizes.push_back({types[i], 1});
  }
  c.setLayout = createSetLayout(ctx, bindings);
  c.pipelineLayout = createPipelineLayout(ctx, c.setLayout, VK_SHADER_STAGE_COMPUTE_BIT, pushBytes);
  c.pool = createPool(ctx, sizes, 1);
  VkDescriptorSetLayout sl = c.setLayout;
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = c.pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &sl;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device(), &ai, &c.set));
  return c;
}

void writeStorageBuffers(const Context& ctx, VkDescriptorSet set, std::span<const VkBuffer> buffers) {
  std::vector<VkDescriptorBufferInfo> infos;
  for (VkBuffer b : buffers) infos.push_back({b, 0, VK_WHOLE_SIZE});
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (uint32_t i = 0; i < buffers.size(); ++i) {
    writes[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx.device(), uint32_t(writes.size()), writes.data(), 0, nullptr);
}

}  // namespace raybudget::vk
