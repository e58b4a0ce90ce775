// The ray-tracing stage's deadline on the device's clock (shaders/include/stage_clock.glsl):
// the trace passes and the fill stop tracing once the stage has run for T, so a frame whose
// selection was predicted wrong (a camera jump that left many more shadow pixels uncertain)
// holds T with fewer pixels traced. The clock's unit is the device's (VK_KHR_shader_clock does
// not name it: nanoseconds on NVIDIA, lavapipe's own), so ticks per millisecond are learned
// from each frame's span of coverage, select and the shadow pass on it against the same
// passes' timestamps.
#pragma once
#include <cstdint>

#include "select/cost_model.h"

namespace raybudget::select {

class StageDeadline {
 public:
  // A frame's span on the device clock from coverage's start to the end of the shadow pass (or
  // of the select pass, where no shadow pass ran), and those passes' timestamps.
  void learn(uint32_t spanTicks, double spanMs);
  bool calibrated() const { return !ticksPerMs_.empty(); }
  double ticksPerMs() const { return ticksPerMs_.value(); }
  // T in device-clock ticks after the stage began, less the share kept for what runs after the
  // deadline (the subgroups under way, the leave-outs of the rest); 0, no deadline, before the
  // clock was calibrated or where T is past the clock's 32-bit span.
  uint32_t ticks(double budgetMs) const;
  void forget() { ticksPerMs_.clear(); }

  // The share of T the passes keep after the deadline: the subgroups already tracing finish
  // their pixels, and the rest of the passes' invocations note what they leave out.
  static constexpr double kDrainShare = 0.03;

 private:
  RecentMedian ticksPerMs_;
};

}  // namespace raybudget::select
