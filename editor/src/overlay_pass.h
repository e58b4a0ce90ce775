// The viewport pass: a compute shader (shaders/editor/overlay.comp) reads the core's
// composed frame, traced mask and G-buffer's object IDs, blends the overlay's per-object or
// per-pixel tint,
// outlines the picked object, writes the viewport image the canvas shows, and reads back
// the object ID at a pixel for picking.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "raybudget/core.h"
#include "pass_objects.h"
#include "window_device.h"

namespace raybudget::editor {

class OverlayPass {
 public:
  static constexpr uint32_t kNoObject = 0xFFFFFFFFu;

  OverlayPass(const WindowDevice& wd, const core::Context& core, VkExtent2D size, uint32_t objectCount);

  // Writes the tints the next record() uses (one per object; the GPU is idle).
  void setTints(const std::vector<glm::vec4>& tints);
  // Records the pass after core::Context::recordFrame; leaves viewport() in
  // TRANSFER_SRC_OPTIMAL. `pick`: the pixel whose object ID pickedId() returns after the
  // frame completed (negative: none). `showTraced`: tint the pixels the core traced, per
  // effect (its traced mask).
  void record(VkCommandBuffer cmd, glm::ivec2 pick, uint32_t highlight, bool showTraced);
  uint32_t pickedId() const;
  VkImage viewport() const { return viewport_.image; }
  VkExtent2D extent() const { return viewport_.extent; }

 private:
  VkExtent2D size_;
  uint32_t objectCount_;
  DeviceImage viewport_;
  bool viewportInitialised_ = false;
  Owned<VkImageView> objectIdView_;
  Owned<VkSampler> sampler_;
  HostBuffer tints_, pick_;
  DescriptorSet descriptors_;
  Owned<VkPipelineLayout> pipelineLayout_;
  Owned<VkPipeline> pipeline_;
};

}  // namespace raybudget::editor
