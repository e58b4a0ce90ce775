// Draws Dear ImGui's draw data inside the canvas's UI render pass with a pipeline of ours
// (shaders/editor/ui.vert, ui.frag): the font atlas as one R8 coverage texture, the vertices
// and indices in host-visible buffers that grow as needed. It takes the place of the Vulkan
// backend of Debian's Dear ImGui 1.86 for one reason: the index order. On lavapipe the UI
// pass costs per primitive (a glyph ~1-2 us, nearly all in rasterising it), and llvmpipe
// rasterises two triangles that form a rectangle as one, in about 8% less UI time here, only
// when they come in aligned pairs in draws of at most 1020 indices (quad_pairs.h).
// One frame in flight: the editor waits for each frame before the next writes the buffers.
#pragma once
#include <vector>

#include <imgui.h>

#include "pass_objects.h"
#include "window_device.h"

namespace raybudget::editor {

class UiRenderer {
 public:
  // Uploads ImGui's font atlas (the current context's) and builds the pipeline for
  // `renderPass`'s subpass 0.
  UiRenderer(const WindowDevice& wd, VkRenderPass renderPass);

  // Records `data` into `cmd`, inside the render pass.
  void record(VkCommandBuffer cmd, const ImDrawData& data);

 private:
  void uploadFontAtlas();
  void reserve(HostBuffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage);

  const WindowDevice& wd_;
  DeviceImage atlas_;
  Owned<VkSampler> sampler_;
  DescriptorSet descriptors_;
  Owned<VkPipelineLayout> pipelineLayout_;
  Owned<VkPipeline> pipeline_;
  HostBuffer vertices_, indices_;
  std::vector<ImDrawIdx> indexData_;  // the frame's indices, quads paired (kept: no allocation per frame)
};

}  // namespace raybudget::editor
