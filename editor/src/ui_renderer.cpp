#include "ui_renderer.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>
#include <vector>

#include "quad_pairs.h"
#include "ui_frag.h"
#include "ui_vert.h"

namespace raybudget::editor {
namespace {

struct UiPush {
  float scale[2];
  float translate[2];
};

constexpr VkIndexType kIndexType = sizeof(ImDrawIdx) == 2 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32;

Owned<VkPipeline> uiPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass renderPass) {
  const Owned<VkShaderModule> vert = makeShaderModule(device, kSpirv_ui_vert, sizeof(kSpirv_ui_vert));
  const Owned<VkShaderModule> frag = makeShaderModule(device, kSpirv_ui_frag, sizeof(kSpirv_ui_frag));
  const VkPipelineShaderStageCreateInfo stages[] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vert, "main", nullptr},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, frag, "main", nullptr}};
  const VkVertexInputBindingDescription binding{0, sizeof(ImDrawVert), VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription attributes[] = {{0, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(ImDrawVert, pos)},
                                                          {1, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(ImDrawVert, uv)},
                                                          {2, 0, VK_FORMAT_R8G8B8A8_UNORM, offsetof(ImDrawVert, col)}};
  VkPipelineVertexInputStateCreateInfo input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  input.vertexBindingDescriptionCount = 1;
  input.pVertexBindingDescriptions = &binding;
  input.vertexAttributeDescriptionCount = 3;
  input.pVertexAttributeDescriptions = attributes;
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  // Straight alpha over the canvas, which stays opaque.
  VkPipelineColorBlendAttachmentState blend{};
  blend.blendEnable = VK_TRUE;
  blend.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
  blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
  blend.colorBlendOp = VK_BLEND_OP_ADD;
  blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
  blend.alphaBlendOp = VK_BLEND_OP_ADD;
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo colour{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  colour.attachmentCount = 1;
  colour.pAttachments = &blend;
  const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamicState{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamicState.dynamicStateCount = 2;
  dynamicState.pDynamicStates = dynamic;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &input;
  ci.pInputAssemblyState = &assembly;
  ci.pViewportState = &viewport;
  ci.pRasterizationState = &raster;
  ci.pMultisampleState = &multisample;
  ci.pDepthStencilState = &depth;
  ci.pColorBlendState = &colour;
  ci.pDynamicState = &dynamicState;
  ci.layout = layout;
  ci.renderPass = renderPass;
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline), "vkCreateGraphicsPipelines");
  return Owned<VkPipeline>(pipeline, [device](VkPipeline p) { vkDestroyPipeline(device, p, nullptr); });
}

}  // namespace

UiRenderer::UiRenderer(const WindowDevice& wd, VkRenderPass renderPass) : wd_(wd) {
  const VkDevice device = wd.device();
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;  // as ImGui's: its anti-aliased lines read baked texels between them
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sampler_ = make(device, vkCreateSampler, vkDestroySampler, si, "vkCreateSampler");

  const VkDescriptorType atlas = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  descriptors_ = makeDescriptorSet(device, {&atlas, 1}, VK_SHADER_STAGE_FRAGMENT_BIT);
  pipelineLayout_ = makePipelineLayout(device, descriptors_.layout, VK_SHADER_STAGE_VERTEX_BIT, sizeof(UiPush));
  pipeline_ = uiPipeline(device, pipelineLayout_, renderPass);

  uploadFontAtlas();
  const VkDescriptorImageInfo image{sampler_, atlas_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = descriptors_.set;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  write.pImageInfo = &image;
  vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);

  ImGuiIO& io = ImGui::GetIO();
  io.BackendRendererName = "raybudget_editor_ui";
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;  // draws pass ImDrawCmd::VtxOffset
}

void UiRenderer::uploadFontAtlas() {
  ImGuiIO& io = ImGui::GetIO();
  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  io.Fonts->GetTexDataAsAlpha8(&pixels, &width, &height);
  if (!pixels || width <= 0 || height <= 0) throw Error("editor: Dear ImGui built no font atlas");
  const VkExtent2D extent{uint32_t(width), uint32_t(height)};
  atlas_ = createImage(wd_, VK_FORMAT_R8_UNORM, extent, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  const HostBuffer staging = createHostBuffer(wd_, VkDeviceSize(width) * VkDeviceSize(height), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.mapped, pixels, staging.size);

  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = wd_.commandPool();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(wd_.device(), &ai, &cmd), "vkAllocateCommandBuffers");
  const VkDevice device = wd_.device();
  const VkCommandPool commandPool = wd_.commandPool();
  const Owned<VkCommandBuffer> owned(cmd, [device, commandPool](VkCommandBuffer c) { vkFreeCommandBuffers(device, commandPool, 1, &c); });
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  imageBarrier(cmd, atlas_.image, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
               VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyBufferToImage(cmd, staging.buffer, atlas_.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  imageBarrier(cmd, atlas_.image, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
               VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  check(vkQueueSubmit(wd_.queue(), 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit");
  check(vkQueueWaitIdle(wd_.queue()), "vkQueueWaitIdle");
  io.Fonts->SetTexID(ImTextureID(descriptors_.set));
}

void UiRenderer::reserve(HostBuffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage) {
  if (buffer.size >= bytes) return;
  buffer = createHostBuffer(wd_, std::bit_ceil(std::max<VkDeviceSize>(bytes, 64 * 1024)), usage);
}

void UiRenderer::record(VkCommandBuffer cmd, const ImDrawData& data) {
  const float fbWidth = data.DisplaySize.x * data.FramebufferScale.x, fbHeight = data.DisplaySize.y * data.FramebufferScale.y;
  if (data.TotalVtxCount <= 0 || fbWidth <= 0.0f || fbHeight <= 0.0f) return;

  // The draws: per command its clip rectangle in framebuffer pixels (within it) and its
  // indices, quads paired (quad_pairs.h), cut into draws of at most kIndicesPerDraw:
  // llvmpipe's draw module splits longer ones into runs of 1023 indices, breaking the pairs.
  constexpr uint32_t kIndicesPerDraw = 1020;
  struct Draw {
    VkRect2D scissor;
    uint32_t firstIndex, count;
    int32_t vertexOffset;
  };
  std::vector<Draw> draws;
  indexData_.clear();
  int32_t listVertices = 0;
  for (int l = 0; l < data.CmdListsCount; ++l) {
    const ImDrawList& list = *data.CmdLists[l];
    for (const ImDrawCmd& c : list.CmdBuffer) {
      if (c.UserCallback) {  // the editor's panels add none; honour them as ImGui's backends do
        if (c.UserCallback != ImDrawCallback_ResetRenderState) c.UserCallback(&list, &c);
        continue;
      }
      const float x0 = std::max(0.0f, (c.ClipRect.x - data.DisplayPos.x) * data.FramebufferScale.x);
      const float y0 = std::max(0.0f, (c.ClipRect.y - data.DisplayPos.y) * data.FramebufferScale.y);
      const float x1 = std::min(fbWidth, (c.ClipRect.z - data.DisplayPos.x) * data.FramebufferScale.x);
      const float y1 = std::min(fbHeight, (c.ClipRect.w - data.DisplayPos.y) * data.FramebufferScale.y);
      if (x1 <= x0 || y1 <= y0) continue;
      const VkRect2D scissor{{int32_t(x0), int32_t(y0)}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
      const uint32_t first = uint32_t(indexData_.size());
      appendPairedQuads(list.IdxBuffer.Data + c.IdxOffset, c.ElemCount, indexData_);
      for (uint32_t i = first; i < indexData_.size(); i += kIndicesPerDraw)
        draws.push_back({scissor, i, std::min<uint32_t>(kIndicesPerDraw, uint32_t(indexData_.size()) - i), listVertices + int32_t(c.VtxOffset)});
    }
    listVertices += list.VtxBuffer.Size;
  }
  if (draws.empty()) return;

  reserve(vertices_, VkDeviceSize(data.TotalVtxCount) * sizeof(ImDrawVert), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  reserve(indices_, VkDeviceSize(indexData_.size()) * sizeof(ImDrawIdx), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  auto* vertexOut = static_cast<ImDrawVert*>(vertices_.mapped);
  for (int l = 0; l < data.CmdListsCount; ++l) vertexOut = std::copy(data.CmdLists[l]->VtxBuffer.begin(), data.CmdLists[l]->VtxBuffer.end(), vertexOut);
  std::memcpy(indices_.mapped, indexData_.data(), indexData_.size() * sizeof(ImDrawIdx));

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, vertices_.buffer.ptr(), &zero);
  vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, kIndexType);
  const VkViewport viewport{0.0f, 0.0f, fbWidth, fbHeight, 0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  UiPush push{{2.0f / data.DisplaySize.x, 2.0f / data.DisplaySize.y}, {}};
  push.translate[0] = -1.0f - data.DisplayPos.x * push.scale[0];
  push.translate[1] = -1.0f - data.DisplayPos.y * push.scale[1];
  vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout_, 0, 1, &descriptors_.set, 0, nullptr);
  for (const Draw& d : draws) {
    vkCmdSetScissor(cmd, 0, 1, &d.scissor);
    vkCmdDrawIndexed(cmd, d.count, 1, d.firstIndex, d.vertexOffset, 0);
  }
}

}  // namespace raybudget::editor
