#include "vk/resources.h"

#include <algorithm>
#include <cstring>

#include "vk/check.h"

namespace raybudget::vk {
namespace {

Owned<VkDeviceMemory> allocate(const Context& ctx, const VkMemoryRequirements& req, VkMemoryPropertyFlags flags, bool deviceAddress = false) {
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  VkMemoryAllocateFlagsInfo fi{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  fi.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  if (deviceAddress) ai.pNext = &fi;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, flags);
  VkDeviceMemory mem = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateMemory(ctx.device(), &ai, nullptr, &mem));
  const VkDevice device = ctx.device();
  std::shared_ptr<std::atomic<uint64_t>> counter = ctx.allocationCounter();
  *counter += req.size;
  return Owned<VkDeviceMemory>(mem, [device, counter, size = req.size](VkDeviceMemory m) {
    vkFreeMemory(device, m, nullptr);
    *counter -= size;
  });
}

}  // namespace

Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible) {
  const VkDevice device = ctx.device();
  Buffer b;
  b.size = std::max<VkDeviceSize>(size, 16);
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = b.size;
  ci.usage = usage;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buf = VK_NULL_HANDLE;
  VK_CHECK(vkCreateBuffer(device, &ci, nullptr, &buf));
  b.buffer = Owned<VkBuffer>(buf, [device](VkBuffer x) { vkDestroyBuffer(device, x, nullptr); });
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, buf, &req);
  b.memory = allocate(ctx, req,
                      hostVisible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT,
                      (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0);
  VK_CHECK(vkBindBufferMemory(device, buf, b.memory, 0));
  if (hostVisible) VK_CHECK(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
  return b;
}

VkDeviceAddress bufferAddress(const Context& ctx, const Buffer& buffer) {
  VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  info.buffer = buffer.buffer;
  return vkGetBufferDeviceAddress(ctx.device(), &info);
}

Buffer createDeviceBuffer(const Context& ctx, const void* bytes, VkDeviceSize size, VkBufferUsageFlags usage) {
  Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
  std::memcpy(staging.mapped, bytes, size_t(size));
  Buffer b = createBuffer(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy copy{0, 0, size};
    vkCmdCopyBuffer(cmd, staging.buffer, b.buffer, 1, &copy);
  });
  return b;
}

Image createImage(const Context& ctx, const ImageDesc& desc) {
  const VkDevice device = ctx.device();
  Image img;
  img.desc = desc;
  const bool depth = desc.format == VK_FORMAT_D32_SFLOAT || desc.format == VK_FORMAT_D16_UNORM;
  img.aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.flags = desc.cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = desc.format;
  ci.extent = {desc.width, desc.height, 1};
  ci.mipLevels = desc.mips;
  ci.arrayLayers = desc.layers;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = desc.usage;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image = VK_NULL_HANDLE;
  VK_CHECK(vkCreateImage(device, &ci, nullptr, &image));
  img.image = Owned<VkImage>(image, [device](VkImage x) { vkDestroyImage(device, x, nullptr); });
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, image, &req);
  img.memory = allocate(ctx, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VK_CHECK(vkBindImageMemory(device, image, img.memory, 0));
  const VkImageViewType type = desc.cube ? (desc.layers > 6 ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY : VK_IMAGE_VIEW_TYPE_CUBE)
                               : desc.layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                                 : VK_IMAGE_VIEW_TYPE_2D;
  img.view = createView(ctx, img, type, 0, desc.mips, 0, desc.layers);
  return img;
}

Owned<VkImageView> createView(const Context& ctx, const Image& image, VkImageViewType type, uint32_t baseMip, uint32_t mipCount,
                              uint32_t baseLayer, uint32_t layerCount) {
  const VkDevice device = ctx.device();
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = image.image;
  vi.viewType = type;
  vi.format = image.desc.format;
  vi.subresourceRange = {image.aspect, baseMip, mipCount, baseLayer, layerCount};
  VkImageView view = VK_NULL_HANDLE;
  VK_CHECK(vkCreateImageView(device, &vi, nullptr, &view));
  return Owned<VkImageView>(view, [device](VkImageView v) { vkDestroyImageView(device, v, nullptr); });
}

Owned<VkBufferView> createTexelView(const Context& ctx, const Buffer& buffer, VkFormat format, VkDeviceSize texelBytes) {
  const VkDeviceSize texels = buffer.size / texelBytes;
  if (texels > ctx.properties().limits.maxTexelBufferElements)
    throw Error("buffer of " + std::to_string(texels) + " texels exceeds the device's maxTexelBufferElements (" +
                std::to_string(ctx.properties().limits.maxTexelBufferElements) + ")");
  const VkDevice device = ctx.device();
  VkBufferViewCreateInfo vi{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  vi.buffer = buffer.buffer;
  vi.format = format;
  vi.offset = 0;
  vi.range = texels * texelBytes;
  VkBufferView view = VK_NULL_HANDLE;
  VK_CHECK(vkCreateBufferView(device, &vi, nullptr, &view));
  return Owned<VkBufferView>(view, [device](VkBufferView v) { vkDestroyBufferView(device, v, nullptr); });
}

void imageBarrier(VkCommandBuffer cmd, const Image& image, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, VkImageLayout oldLayout, VkImageLayout newLayout) {
  imageBarrier(cmd, image.image, image.aspect, srcStage, srcAccess, dstStage, dstAccess, oldLayout, newLayout);
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, VkImageLayout oldLayout, VkImageLayout newLayout) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = oldLayout;
  b.newLayout = newLayout;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                   VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void generateMips(VkCommandBuffer cmd, const Image& image) {
  const uint32_t layers = image.desc.layers;
  auto barrier = [&](uint32_t baseMip, uint32_t count, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 dstStage,
                     VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT;
    b.dstStageMask = dstStage;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image.image;
    b.subresourceRange = {image.aspect, baseMip, count, 0, layers};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
  };
  // Each mip is blitted from the previous one, which first becomes a transfer source.
  for (uint32_t mip = 1; mip < image.desc.mips; ++mip) {
    barrier(mip - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
            VK_ACCESS_2_TRANSFER_READ_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip - 1, 0, layers};
    blit.srcOffsets[1] = {int32_t(std::max(image.desc.width >> (mip - 1), 1u)), int32_t(std::max(image.desc.height >> (mip - 1), 1u)), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 0, layers};
    blit.dstOffsets[1] = {int32_t(std::max(image.desc.width >> mip, 1u)), int32_t(std::max(image.desc.height >> mip, 1u)), 1};
    vkCmdBlitImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                   VK_FILTER_LINEAR);
  }
  // Mips 0..n-2 are transfer sources now, the last one a transfer destination.
  const uint32_t last = image.desc.mips - 1;
  const VkPipelineStageFlags2 readers = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  if (last > 0)
    barrier(0, last, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, readers, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  barrier(last, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, readers, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

void uploadTexture(const Context& ctx, const Image& image, const std::vector<uint8_t>& texels) {
  Buffer staging = createBuffer(ctx, texels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
  std::memcpy(staging.mapped, texels.data(), texels.size());
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    imageBarrier(cmd, image, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {image.aspect, 0, 0, 1};
    copy.imageExtent = {image.desc.width, image.desc.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    generateMips(cmd, image);
  });
}

Owned<VkSampler> createSampler(const Context& ctx, const VkSamplerCreateInfo& info) {
  const VkDevice device = ctx.device();
  VkSampler s = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSampler(device, &info, nullptr, &s));
  return Owned<VkSampler>(s, [device](VkSampler x) { vkDestroySampler(device, x, nullptr); });
}

}  // namespace raybudget::vk
