#include "overlay_pass.h"

#include <algorithm>
#include <cstring>

#include "overlay_comp.h"

namespace raybudget::editor {
namespace {

struct OverlayPush {
  glm::ivec2 size;
  glm::ivec2 pick;
  uint32_t objectCount;
  uint32_t highlight;
  uint32_t showTraced;
  uint32_t pad;
};

}  // namespace

OverlayPass::OverlayPass(const WindowDevice& wd, const core::Context& core, VkExtent2D size, uint32_t objectCount)
    : size_(size), objectCount_(objectCount) {
  const VkDevice device = wd.device();
  viewport_ = createImage(wd, VK_FORMAT_R8G8B8A8_UNORM, size, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = core.ownGBuffer().objectId;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = VK_FORMAT_R32_UINT;
  vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  objectIdView_ = make(device, vkCreateImageView, vkDestroyImageView, vi, "vkCreateImageView");
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sampler_ = make(device, vkCreateSampler, vkDestroySampler, si, "vkCreateSampler");
  tints_ = createHostBuffer(wd, std::max<VkDeviceSize>(1, objectCount) * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  std::memset(tints_.mapped, 0, tints_.size);
  pick_ = createHostBuffer(wd, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  *static_cast<uint32_t*>(pick_.mapped) = kNoObject;

  constexpr uint32_t kBindings = 6;
  const VkDescriptorType types[kBindings] = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,  VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                             VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,  VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                             VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
  descriptors_ = makeDescriptorSet(device, types, VK_SHADER_STAGE_COMPUTE_BIT);
  pipelineLayout_ = makePipelineLayout(device, descriptors_.layout, VK_SHADER_STAGE_COMPUTE_BIT, sizeof(OverlayPush));
  const Owned<VkShaderModule> module = makeShaderModule(device, kSpirv_overlay_comp, sizeof(kSpirv_overlay_comp));
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main", nullptr};
  ci.layout = pipelineLayout_;
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline), "vkCreateComputePipelines");
  pipeline_ = Owned<VkPipeline>(pipeline, [device](VkPipeline p) { vkDestroyPipeline(device, p, nullptr); });

  const core::FrameOutputs out = core.outputs();
  const VkDescriptorImageInfo ldr{VK_NULL_HANDLE, out.ldrView, out.layout};
  const VkDescriptorImageInfo ids{sampler_, objectIdView_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkDescriptorImageInfo view{VK_NULL_HANDLE, viewport_.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo traced{VK_NULL_HANDLE, out.tracedMaskView, out.layout};
  const VkDescriptorBufferInfo tintInfo{tints_.buffer, 0, VK_WHOLE_SIZE}, pickInfo{pick_.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet writes[kBindings]{};
  for (uint32_t i = 0; i < kBindings; ++i) {
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = descriptors_.set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = types[i];
  }
  writes[0].pImageInfo = &ldr;
  writes[1].pImageInfo = &ids;
  writes[2].pImageInfo = &view;
  writes[3].pBufferInfo = &tintInfo;
  writes[4].pBufferInfo = &pickInfo;
  writes[5].pImageInfo = &traced;
  vkUpdateDescriptorSets(device, kBindings, writes, 0, nullptr);
}

void OverlayPass::setTints(const std::vector<glm::vec4>& tints) {
  std::memset(tints_.mapped, 0, tints_.size);
  std::memcpy(tints_.mapped, tints.data(), std::min<size_t>(tints.size() * sizeof(glm::vec4), tints_.size));
}

void OverlayPass::record(VkCommandBuffer cmd, glm::ivec2 pick, uint32_t highlight, bool showTraced) {
  // The core's compose and trace passes (compute), its traced mask's clear and its G-buffer
  // raster (colour attachment) write what is read here.
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  mb.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  mb.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cmd, &dep);
  imageBarrier(cmd, viewport_.image, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
               VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, viewportInitialised_ ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_GENERAL);
  viewportInitialised_ = true;
  *static_cast<uint32_t*>(pick_.mapped) = kNoObject;
  const OverlayPush push{glm::ivec2(size_.width, size_.height), pick, objectCount_, highlight, showTraced ? 1u : 0u, 0};
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &descriptors_.set, 0, nullptr);
  vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  vkCmdDispatch(cmd, (size_.width + 7) / 8, (size_.height + 7) / 8, 1);
  imageBarrier(cmd, viewport_.image, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
               VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  // The picked ID and the next frame's host writes of the tints and the pick word.
  VkMemoryBarrier2 host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  host.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  host.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
  host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
  dep.pMemoryBarriers = &host;
  vkCmdPipelineBarrier2(cmd, &dep);
}

uint32_t OverlayPass::pickedId() const { return *static_cast<const uint32_t*>(pick_.mapped); }

}  // namespace raybudget::editor
