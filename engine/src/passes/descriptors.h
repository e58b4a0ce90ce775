// The descriptor bindings (bindings.h): each one's type, and the writes that point them at
// the scene's buffers and the frame's images (each pass's set holds some: pass_layouts.h).
#pragma once
#include <span>
#include <utility>
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

// The descriptor type and count of `binding` (bindings.h).
std::pair<VkDescriptorType, uint32_t> bindingType(uint32_t binding, uint32_t textureCount, bool nativeTracer);

// Points the bindings `only` (sorted) of `set` at their resources; `uniforms` is the slot's
// FrameUniforms; `gbuffer` the views the G-buffer bindings read (the targets' own or a host's).
void writeSet(const vk::Context& ctx, VkDescriptorSet set, std::span<const uint32_t> only, const vk::Buffer& uniforms, const SceneGpu& scene,
              const FrameTargets& targets, const core::GBuffer& gbuffer, const select::SelectionBuffers& selection, const Samplers& samplers);

// kGDepth..kGMaterialId and kGPosition: what a host's G-buffer replaces.
bool isGBufferBinding(uint32_t binding);

}  // namespace raybudget::passes
