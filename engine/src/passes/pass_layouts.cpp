#include "passes/pass_layouts.h"

#include <algorithm>
#include <map>

#include "passes/descriptors.h"
#include "shared/types.h"
#include "vk/check.h"
#include "vk/compute_set.h"
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
  l.setLayout = vk::createSetLayout(ctx_, bindings);
  l.pipelineLayout = vk::createPipelineLayout(ctx_, l.setLayout, VK_SHADER_STAGE_ALL, sizeof(gpu::DrawPush));
  if (l.bindings.empty()) counts[VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER] = 1;  // a pool needs a size; the (empty) set is still bound
  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& [type, count] : counts) sizes.push_back({type, count});
  l.pool = vk::createPool(ctx_, sizes, slots_);
  const std::vector<VkDescriptorSetLayout> layouts(slots_, l.setLayout.get());
  l.sets.resize(slots_);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = l.pool;
  ai.descriptorSetCount = slots_;
  ai.pSetLayouts = layouts.data();
  VK_CHECK(vkAllocateDescriptorSets(ctx_.device(), &ai, l.sets.data()));
  return l;
}

void PassLayouts::writeAll(uint32_t slot, const std::function<void(VkDescriptorSet, std::span<const uint32_t>)>& write) const {
  for (const PassLayout& l : layouts_) write(l.sets.at(slot), l.bindings);
}

}  // namespace raybudget::passes
