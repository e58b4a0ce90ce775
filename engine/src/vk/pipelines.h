// Shader modules and pipelines from the SPIR-V compiled into the binary at build time.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::vk {

using Spirv = std::span<const uint32_t>;

// Workgroups of `groupSize` lanes covering `items` invocations (the last one partial): the
// one place a dispatch size is derived from a shader's local size.
constexpr uint32_t groupsFor(uint32_t items, uint32_t groupSize) { return (items + groupSize - 1) / groupSize; }

Owned<VkPipeline> createComputePipeline(const Context& ctx, VkPipelineLayout layout, Spirv code,
                                        const VkSpecializationInfo* specialization = nullptr);

struct GraphicsPipelineDesc {
  Spirv vertex;
  Spirv fragment;  // may be empty for depth-only passes
  std::vector<VkFormat> colorFormats;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  bool depthBias = false;  // dynamic depth bias (shadow maps)
};

// Dynamic rendering (no render pass objects), no vertex input (vertices are pulled from a
// storage buffer), no culling (double-sided and mirrored instances are handled in shaders),
// depth test LESS, dynamic viewport and scissor.
Owned<VkPipeline> createGraphicsPipeline(const Context& ctx, VkPipelineLayout layout, const GraphicsPipelineDesc& desc);

}  // namespace raybudget::vk
