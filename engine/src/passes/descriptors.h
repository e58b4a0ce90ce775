// The shared descriptor set layout (see bindings.h), its pool, and the writes that point
// each binding at the scene's buffers and the frame's images.
#pragma once
#include <vector>

#include "passes/frame_targets.h"
#include "passes/scene_gpu.h"
#include "select/selection_buffers.h"
#include "vk/context.h"
#include "vk/device_requirements.h"
#include "vk/owned.h"
#include "vk/resources.h"

namespace raybudget::passes {

struct Samplers {
  vk::Owned<VkSampler> nearest;  // G-buffer texelFetch
  vk::Owned<VkSampler> shadow;   // depth compare, LESS_OR_EQUAL
  vk::Owned<VkSampler> linear;   // environment cube maps, trilinear
  vk::Owned<VkSampler> equirect; // HDR environment image: wraps in u
};

Samplers createSamplers(const vk::Context& ctx);

// The descriptors every stage sees through the set's layout (the device's per-stage limits).
vk::DescriptorNeeds descriptorNeeds(uint32_t textureCount, bool nativeTracer);

vk::Owned<VkDescriptorSetLayout> createSetLayout(const vk::Context& ctx, uint32_t textureCount, bool nativeTracer);
vk::Owned<VkDescriptorPool> createPool(const vk::Context& ctx, uint32_t sets, uint32_t textureCount, bool nativeTracer);
VkDescriptorSet allocateSet(const vk::Context& ctx, VkDescriptorPool pool, VkDescriptorSetLayout layout);

// Points every binding of `set` at its resource; `uniforms` is the slot's FrameUniforms.
void writeSet(const vk::Context& ctx, VkDescriptorSet set, const vk::Buffer& uniforms, const SceneGpu& scene, const FrameTargets& targets,
              const select::SelectionBuffers& selection, const Samplers& samplers);

}  // namespace raybudget::passes
