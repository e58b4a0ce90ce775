#include "vk/compute_set.h"

#include <vector>

#include "vk/check.h"

namespace raybudget::vk {

ComputeSet createComputeSet(const Context& ctx, std::span<const VkDescriptorType> types, uint32_t pushBytes) {
  const VkDevice device = ctx.device();
  ComputeSet c;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  std::vector<VkDescriptorPoolSize> sizes;
  for (uint32_t i = 0; i < types.size(); ++i) {
    bindings.push_back({i, types[i], 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    sizes.push_back({types[i], 1});
  }
  VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  lci.bindingCount = uint32_t(bindings.size());
  lci.pBindings = bindings.data();
  VkDescriptorSetLayout sl = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorSetLayout(device, &lci, nullptr, &sl));
  c.setLayout = Owned<VkDescriptorSetLayout>(sl, [device](VkDescriptorSetLayout x) { vkDestroyDescriptorSetLayout(device, x, nullptr); });
  const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
  VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pci.setLayoutCount = 1;
  pci.pSetLayouts = &sl;
  pci.pushConstantRangeCount = pushBytes > 0 ? 1 : 0;
  pci.pPushConstantRanges = &range;
  VkPipelineLayout pl = VK_NULL_HANDLE;
  VK_CHECK(vkCreatePipelineLayout(device, &pci, nullptr, &pl));
  c.pipelineLayout = Owned<VkPipelineLayout>(pl, [device](VkPipelineLayout x) { vkDestroyPipelineLayout(device, x, nullptr); });
  VkDescriptorPoolCreateInfo dci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dci.maxSets = 1;
  dci.poolSizeCount = uint32_t(sizes.size());
  dci.pPoolSizes = sizes.data();
  VkDescriptorPool p = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(device, &dci, nullptr, &p));
  c.pool = Owned<VkDescriptorPool>(p, [device](VkDescriptorPool x) { vkDestroyDescriptorPool(device, x, nullptr); });
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = p;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &sl;
  VK_CHECK(vkAllocateDescriptorSets(device, &ai, &c.set));
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
