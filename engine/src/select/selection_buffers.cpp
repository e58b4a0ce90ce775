#include "select/selection_buffers.h"

#include <algorithm>

#include "select/object_params.h"
#include "shared/config.h"
#include "vk/check.h"
#include "vk/pipelines.h"

namespace raybudget::select {

std::vector<gpu::GpuObjectParams> initialObjectParams(const Scene& scene, float maxRoughness) {
  std::vector<gpu::GpuObjectParams> params;
  for (const Object& o : scene.objects) {
    const ObjectParams p = objectParams(scene, o, maxRoughness);
    params.push_back({glm::vec4(p.K, p.Q, p.I, 0.0f), glm::vec4(itemPriors(scene, o), 0.0f)});
  }
  if (params.empty()) params.push_back({});  // a buffer is never empty
  return params;
}

SelectionBuffers createSelectionBuffers(const vk::Context& ctx, uint32_t objects, const std::vector<gpu::GpuObjectParams>& params,
                                        uint32_t width, uint32_t height) {
  constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  constexpr VkBufferUsageFlags kCopy = VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  SelectionBuffers b;
  b.objects = objects;
  b.tiles = vk::groupsFor(width, RB_TILE_SIZE) * vk::groupsFor(height, RB_TILE_SIZE);
  const VkDeviceSize records = std::max<VkDeviceSize>(1, b.objects);
  b.coverage = vk::createBuffer(ctx, records * sizeof(gpu::GpuCoverage), kStorage | kCopy, false);
  b.objectParams = vk::createDeviceBuffer(ctx, params, kStorage | kCopy);
  b.objectRecords = vk::createBuffer(ctx, records * sizeof(gpu::GpuObjectRecord), kStorage | kCopy, false);
  b.selection = vk::createBuffer(ctx, records * sizeof(uint32_t), kStorage | kCopy, false);
  b.objectCosts = vk::createDeviceBuffer(ctx, std::vector<gpu::GpuObjectCost>(records), kStorage | kCopy);
  b.itemCosts = vk::createDeviceBuffer(ctx, std::vector<gpu::GpuItemCost>(records * RB_ITEMS_PER_OBJECT + 1), kStorage | kCopy);
  b.tileObjects = vk::createBuffer(ctx, 4ull * RB_TILE_OBJECT_WORDS * b.tiles, kStorage, false);
  b.tileList = vk::createBuffer(ctx, kTileListHeaderBytes + 4ull * kTileListWordsPerTile * b.tiles, kStorage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | kCopy, false);
  return b;
}

void recordSelectionReset(VkCommandBuffer cmd, const SelectionBuffers& buffers, const std::vector<gpu::GpuObjectParams>& params) {
  constexpr size_t kPerUpdate = 65536 / sizeof(gpu::GpuObjectParams);  // vkCmdUpdateBuffer's limit
  for (size_t first = 0; first < params.size(); first += kPerUpdate) {
    const size_t count = std::min(kPerUpdate, params.size() - first);
    vkCmdUpdateBuffer(cmd, buffers.objectParams.buffer, first * sizeof(gpu::GpuObjectParams), count * sizeof(gpu::GpuObjectParams),
                      &params[first]);
  }
  vkCmdFillBuffer(cmd, buffers.objectCosts.buffer, 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, buffers.itemCosts.buffer, 0, VK_WHOLE_SIZE, 0);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                    VK_ACCESS_2_MEMORY_READ_BIT);
}

}  // namespace raybudget::select
