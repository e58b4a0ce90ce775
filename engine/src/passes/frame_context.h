// What a pass needs to record itself into a frame's command buffer.
#pragma once
#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "passes/frame_targets.h"
#include "passes/scene_gpu.h"
#include "select/selection_buffers.h"

namespace raybudget::passes {

struct FrameContext {
  VkCommandBuffer cmd;
  uint32_t slot;  // the frame slot: each pass binds its own set for it (pass_layouts.h)
  const SceneGpu& scene;
  const FrameTargets& targets;
  const select::SelectionBuffers& selection;
  glm::mat4 viewProj;  // the camera's
};

// True when a bounding sphere may intersect the frustum of `viewProj` (Vulkan clip space,
// depth 0..1). Planes are taken from the matrix rows (Gribb & Hartmann).
bool sphereInFrustum(const glm::mat4& viewProj, const glm::vec4& sphere);

}  // namespace raybudget::passes
