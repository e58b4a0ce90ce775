#include "passes/bvh_buffers.h"

namespace raybudget::passes {

BvhBuffers uploadBvh(const vk::Context& ctx, const bvh::SceneBvh& bvh, bool updatable) {
  const VkBufferUsageFlags update = updatable ? VK_BUFFER_USAGE_TRANSFER_DST_BIT : 0;
  BvhBuffers b;
  b.nodes = vk::createDeviceBuffer(ctx, bvh.nodes, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | update);
  b.triangles = vk::createDeviceBuffer(ctx, bvh.triangles, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
  b.instances = vk::createDeviceBuffer(ctx, bvh.instances, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | update);
  // Unsigned texels: node and triangle words hold integer bits, which a GPU's texture unit
  // could flush as float denormals.
  b.nodeTexels = vk::createTexelView(ctx, b.nodes, VK_FORMAT_R32G32B32A32_UINT, 16);
  b.triangleTexels = vk::createTexelView(ctx, b.triangles, VK_FORMAT_R32G32B32A32_UINT, 16);
  return b;
}

}  // namespace raybudget::passes
