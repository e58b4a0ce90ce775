// The select pass: which objects get ray-traced effects (shaders/select/select_unbudgeted.comp), then the list
// of 8x8 tiles holding their pixels, whose count is the trace passes' indirect dispatch
// (shaders/select/tile_list.comp). Reads the object records of the coverage pass.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::select {

// None / All write the selection; Keep leaves the one the GPU selector wrote.
enum class SelectMode : uint32_t { None = 0, All = 1, Keep = 2 };

class SelectPass {
 public:
  SelectPass(const vk::Context& ctx, passes::PassLayouts& layouts);
  // Barriers included: afterwards the tile list is ready for indirect dispatch and reads.
  // `rate`: RB_RATE_* of every selected item (All).
  void record(const passes::FrameContext& fc, SelectMode mode, uint32_t rate) const;

 private:
  const passes::PassLayout& layout_;
  vk::Owned<VkPipeline> select_;
  vk::Owned<VkPipeline> tiles_;
};

}  // namespace raybudget::select
