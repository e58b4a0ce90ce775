// A timestamp query pool with one range per frame slot; every pass writes a begin and an
// end stamp. Results are read when the slot's fence has signalled, never waited for.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::vk {

class TimestampPool {
 public:
  TimestampPool(const Context& ctx, uint32_t slots, uint32_t passes);

  // Resets the slot's queries; call at the start of the slot's command buffer.
  void reset(VkCommandBuffer cmd, uint32_t slot);
  void begin(VkCommandBuffer cmd, uint32_t slot, uint32_t pass);
  void end(VkCommandBuffer cmd, uint32_t slot, uint32_t pass);

  // Milliseconds each pass of the slot took, nullopt for passes not recorded; non-blocking:
  // a pass whose results are not yet available also gives nullopt.
  std::vector<std::optional<double>> read(uint32_t slot);

 private:
  void stamp(VkCommandBuffer cmd, uint32_t query);
  VkDevice device_;
  Owned<VkQueryPool> pool_;
  uint32_t passes_;
  double nsPerTick_;
  uint64_t validMask_;
  bool flushAfterStamp_;  // a CPU device (lavapipe) defers binned work: see stamp()
  std::vector<std::vector<bool>> written_;  // [slot][pass]
};

}  // namespace raybudget::vk
