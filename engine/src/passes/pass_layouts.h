// Every pass binds what its shaders read and write, at the pass: its descriptor set layout
// holds just the bindings its shaders use (found in their SPIR-V, vk/spirv_bindings.h), with
// the binding numbers of bindings.h, and it gets one set per frame slot. The registry makes
// them while the passes are built and writes them once every resource exists.
#pragma once
#include <cstdint>
#include <deque>
#include <functional>
#include <initializer_list>
#include <span>
#include <vector>

#include "passes/frame_context.h"
#include "vk/context.h"
#include "vk/owned.h"
#include "vk/pipelines.h"

namespace raybudget::passes {

struct PassLayout {
  std::vector<uint32_t> bindings;  // sorted
  vk::Owned<VkDescriptorSetLayout> setLayout;
  vk::Owned<VkPipelineLayout> pipelineLayout;  // the set and one push-constant range (gpu::DrawPush)
  vk::Owned<VkDescriptorPool> pool;
  std::vector<VkDescriptorSet> sets;  // per frame slot

  void bind(const FrameContext& fc, VkPipelineBindPoint point) const;
  template <typename T>
  void push(const FrameContext& fc, const T& constants) const {
    vkCmdPushConstants(fc.cmd, pipelineLayout, VK_SHADER_STAGE_ALL, 0, sizeof(T), &constants);
  }
};

class PassLayouts {
 public:
  PassLayouts(const vk::Context& ctx, uint32_t textureCount, bool nativeTracer, uint32_t slots);
  // The layout for a pass whose pipelines use `shaders` (the union of their bindings).
  const PassLayout& create(std::initializer_list<vk::Spirv> shaders);
  // Calls `write(set, bindings)` for every pass's set of `slot`.
  void writeAll(uint32_t slot, const std::function<void(VkDescriptorSet, std::span<const uint32_t>)>& write) const;

 private:
  const vk::Context& ctx_;
  uint32_t textureCount_;
  bool native_;
  uint32_t slots_;
  std::deque<PassLayout> layouts_;  // stable addresses: passes keep references
};

}  // namespace raybudget::passes
