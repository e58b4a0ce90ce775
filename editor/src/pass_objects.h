// What each of the editor's own passes (overlay_pass, ui_renderer) makes alike: one descriptor
// set of given bindings with its layout and pool, a pipeline layout of that set and one push
// constant range, and a shader module from compiled SPIR-V.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "owned.h"

namespace raybudget::editor {

struct DescriptorSet {
  Owned<VkDescriptorSetLayout> layout;
  Owned<VkDescriptorPool> pool;
  VkDescriptorSet set = VK_NULL_HANDLE;  // freed with the pool
};

// A set whose binding i has type types[i], one descriptor each, seen by `stages`.
inline DescriptorSet makeDescriptorSet(VkDevice device, std::span<const VkDescriptorType> types, VkShaderStageFlags stages) {
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  std::vector<VkDescriptorPoolSize> sizes;
  for (uint32_t i = 0; i < types.size(); ++i) {
    bindings.push_back({i, types[i], 1, stages, nullptr});
    sizes.push_back({types[i], 1});
  }
  DescriptorSet d;
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = uint32_t(bindings.size());
  li.pBindings = bindings.data();
  d.layout = make(device, vkCreateDescriptorSetLayout, vkDestroyDescriptorSetLayout, li, "vkCreateDescriptorSetLayout");
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = uint32_t(sizes.size());
  pi.pPoolSizes = sizes.data();
  d.pool = make(device, vkCreateDescriptorPool, vkDestroyDescriptorPool, pi, "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = d.pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = d.layout.ptr();
  check(vkAllocateDescriptorSets(device, &ai, &d.set), "vkAllocateDescriptorSets");
  return d;
}

// A pipeline layout of `setLayout` and push constants of `pushBytes` seen by `stages`.
inline Owned<VkPipelineLayout> makePipelineLayout(VkDevice device, VkDescriptorSetLayout setLayout, VkShaderStageFlags stages, uint32_t pushBytes) {
  const VkPushConstantRange range{stages, 0, pushBytes};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &range;
  return make(device, vkCreatePipelineLayout, vkDestroyPipelineLayout, pli, "vkCreatePipelineLayout");
}

inline Owned<VkShaderModule> makeShaderModule(VkDevice device, const uint32_t* code, size_t bytes) {
  VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  mi.codeSize = bytes;
  mi.pCode = code;
  return make(device, vkCreateShaderModule, vkDestroyShaderModule, mi, "vkCreateShaderModule");
}

}  // namespace raybudget::editor
