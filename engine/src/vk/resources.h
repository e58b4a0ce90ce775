// Buffers and images with their memory, owned; one allocation each (scenes here have
// hundreds of resources at most, far below maxMemoryAllocationCount).
#pragma once
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::vk {

struct Buffer {
  Owned<VkBuffer> buffer;
  Owned<VkDeviceMemory> memory;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // host-visible buffers stay mapped
};

Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible);

// The device address of a buffer created with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT
// (createBuffer then allocates its memory with the device-address flag).
VkDeviceAddress bufferAddress(const Context& ctx, const Buffer& buffer);

// A device-local buffer filled with `bytes` through a staging buffer.
Buffer createDeviceBuffer(const Context& ctx, const void* bytes, VkDeviceSize size, VkBufferUsageFlags usage);

template <typename T>
Buffer createDeviceBuffer(const Context& ctx, const std::vector<T>& data, VkBufferUsageFlags usage) {
  // Empty arrays still get a one-element buffer: descriptors must point somewhere.
  const std::vector<T> one(1);
  const std::vector<T>& src = data.empty() ? one : data;
  return createDeviceBuffer(ctx, src.data(), VkDeviceSize(src.size() * sizeof(T)), usage);
}

struct ImageDesc {
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  uint32_t width = 1;
  uint32_t height = 1;
  uint32_t mips = 1;
  uint32_t layers = 1;
  bool cube = false;  // layers is a multiple of 6 and the view is a cube (array)
  VkImageUsageFlags usage = 0;
};

struct Image {
  Owned<VkImage> image;
  Owned<VkDeviceMemory> memory;
  Owned<VkImageView> view;  // all mips and layers
  ImageDesc desc;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
};

Image createImage(const Context& ctx, const ImageDesc& desc);

// A view of one mip level (all layers) or one layer (one mip), for storage writes and
// render targets.
Owned<VkImageView> createView(const Context& ctx, const Image& image, VkImageViewType type, uint32_t baseMip, uint32_t mipCount,
                              uint32_t baseLayer, uint32_t layerCount);

// Synchronization2 image barrier over the whole image (every mip and layer of `aspect`).
void imageBarrier(VkCommandBuffer cmd, const Image& image, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, VkImageLayout oldLayout, VkImageLayout newLayout);
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, VkImageLayout oldLayout, VkImageLayout newLayout);

// A global memory barrier (buffers, and images whose layout does not change).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                   VkAccessFlags2 dstAccess);

// Fills mips 1.. of every layer by linear blits from mip 0. Expects the whole image in
// TRANSFER_DST_OPTIMAL; leaves it in SHADER_READ_ONLY_OPTIMAL.
void generateMips(VkCommandBuffer cmd, const Image& image);

// Uploads texels (bytes in the image's format) to mip 0 and fills the other mips by linear blits; leaves the image
// in SHADER_READ_ONLY_OPTIMAL.
void uploadTexture(const Context& ctx, const Image& image, const std::vector<uint8_t>& texels);

// A view of a whole buffer as `format` texels, for uniform texel buffers. Throws when the
// buffer holds more texels than the device's maxTexelBufferElements.
Owned<VkBufferView> createTexelView(const Context& ctx, const Buffer& buffer, VkFormat format, VkDeviceSize texelBytes);

Owned<VkSampler> createSampler(const Context& ctx, const VkSamplerCreateInfo& info);

}  // namespace raybudget::vk
