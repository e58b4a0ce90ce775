#include "vk/timestamps.h"

#include "vk/check.h"
#include "vk/resources.h"

namespace raybudget::vk {

TimestampPool::TimestampPool(const Context& ctx, uint32_t slots, uint32_t passes)
    : device_(ctx.device()), passes_(passes), nsPerTick_(ctx.properties().limits.timestampPeriod),
      flushAfterStamp_(ctx.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU),
      written_(slots, std::vector<bool>(passes, false)) {
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &familyCount, families.data());
  const uint32_t bits = families[ctx.queueFamily()].timestampValidBits;
  validMask_ = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = slots * passes * 2;
  VkQueryPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateQueryPool(device_, &ci, nullptr, &pool));
  const VkDevice device = device_;
  pool_ = Owned<VkQueryPool>(pool, [device](VkQueryPool p) { vkDestroyQueryPool(device, p, nullptr); });
}

void TimestampPool::reset(VkCommandBuffer cmd, uint32_t slot) {
  vkCmdResetQueryPool(cmd, pool_, slot * passes_ * 2, passes_ * 2);
  written_[slot].assign(passes_, false);
}

// Lavapipe records a timestamp when it next flushes its binned (raster) work, while compute
// dispatches run at once: without a flush right after the stamp, a compute pass's begin
// stamp lands after its own dispatch. On a CPU device a full barrier after each stamp forces
// that flush; a GPU writes an ALL_COMMANDS stamp once the work before it is done, and gets
// no barrier (a host's own work may overlap the passes there).
void TimestampPool::stamp(VkCommandBuffer cmd, uint32_t query) {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, query);
  if (flushAfterStamp_)
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                  VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

void TimestampPool::begin(VkCommandBuffer cmd, uint32_t slot, uint32_t pass) { stamp(cmd, (slot * passes_ + pass) * 2); }

void TimestampPool::end(VkCommandBuffer cmd, uint32_t slot, uint32_t pass) {
  stamp(cmd, (slot * passes_ + pass) * 2 + 1);
  written_[slot][pass] = true;
}

std::vector<std::optional<double>> TimestampPool::read(uint32_t slot) {
  std::vector<std::optional<double>> out(passes_);
  for (uint32_t pass = 0; pass < passes_; ++pass) {
    if (!written_[slot][pass]) continue;
    uint64_t data[4] = {};  // begin, availability, end, availability
    const VkResult r = vkGetQueryPoolResults(device_, pool_, (slot * passes_ + pass) * 2, 2, sizeof(data), data, 2 * sizeof(uint64_t),
                                             VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
    if (r == VK_NOT_READY || !data[1] || !data[3]) continue;
    VK_CHECK(r);
    const uint64_t ticks = ((data[2] & validMask_) - (data[0] & validMask_)) & validMask_;
    out[pass] = double(ticks) * nsPerTick_ * 1e-6;
  }
  return out;
}

}  // namespace raybudget::vk
