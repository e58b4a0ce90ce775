#include "passes/pass_layouts.h"

#include <algorithm>
#include <map>

#include "passes/descriptors.h"
#include "shared/types.h"
#include "vk/check.h"
#include "vk/spirv_bindings.h"

namespace raybudget::passes {

void PassLayout::bind(const FrameContext& fc, VkPipelineBindPoint point) const {
  vkCmdBindDescriptorSets(fc.cmd, point, pipelineLayout, 0, 1, &sets.at(fc.slot), 0, nullptr);
}

PassLayouts::PassLayouts(const vk::Context& ctx, uint32_t textureCount, bool nativeTracer, uint32_t slots)
    : ctx_(ctx), textureCount_(textureCount), native_(nativeTracer), slots_(slots) {}

const PassLayout& PassLayouts::create(std::initializer_list<vk::Spirv> shaders) {
  PassLayout& l = layouts_.emplace_back();
  for (vk::Spirv code : shaders) {
    const std::vector<uint32_t> used = vk::usedBindings(code);
    l.bindings.insert(l.bindings.end(), used.begin(), used.end());
  }
  std::sort(l.bindings.begin(), l.bindings.end());
  l.bindings.erase(std::unique(l.bindings.begin(), l.bindings.end()), l.bindings.end());

  std::vector<VkDescriptorSetLayoutBinding> bindings;
  std::map<VkDescriptorType, uint32_t> counts;
  for (uint32_t b : l.bindings) {
    const auto [type, count] = bindingType(b, textureCount_, native_);
    bindings.push_back({b, type, count, VK_SHADER_STAGE_ALL, nullptr});
    counts[type] += count * slots_;
  }
  const VkDevice device = ctx_.device();
  VkDescriptorSetLayoutCreateInfo sci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  sci.bindingCount = uint32_t(bindings.size());
  sci.pBindings = bindings.data();
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorSetLayout(device, &sci, nullptr, &setLayout));
  l.setLayout = vk::Owned<VkDescriptorSetLayout>(setLayout, [device](VkDescriptorSetLayout x) { vkDestroyDescriptorSetLayout(device, x, nullptr); });

  const VkPushConstantRange range{VK_SHADER_STAGE_ALL, 0, sizeof(gpu::DrawPush)};
  VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pci.setLayoutCount = 1;
  pci.pSetLayouts = &setLayout;
  pci.pushConstantRangeCount = 1;
  pci.pPushConstantRanges = &range;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VK_CHECK(vkCreatePipelineLayout(device, &pci, nullptr, &pipelineLayout));
  l.pipelineLayout = vk::Owned<VkPipelineLayout>(pipelineLayout, [device](VkPipelineLayout x) { vkDestroyPipelineLayout(device, x, nullptr); });

  if (l.bindings.empty()) {  // a pass reading nothing through descriptors still binds an (empty) set
    counts[VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER] = 1;
  }
  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& [type, count] : counts) sizes.push_back({type, count});
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = slots_;
  poolInfo.poolSizeCount = uint32_t(sizes.size());
  poolInfo.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool));
  l.pool = vk::Owned<VkDescriptorPool>(pool, [device](VkDescriptorPool x) { vkDestroyDescriptorPool(device, x, nullptr); });
  const std::vector<VkDescriptorSetLayout> layouts(slots_, setLayout);
  l.sets.resize(slots_);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool;
  ai.descriptorSetCount = slots_;
  ai.pSetLayouts = layouts.data();
  VK_CHECK(vkAllocateDescriptorSets(device, &ai, l.sets.data()));
  return l;
}

void PassLayouts::writeAll(uint32_t slot, const std::function<void(VkDescriptorSet, std::span<const uint32_t>)>& write) const {
  for (const PassLayout& l : layouts_) write(l.sets.at(slot), l.bindings);
}

}  // namespace raybudget::passes
