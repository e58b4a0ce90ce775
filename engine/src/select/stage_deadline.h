// The ray-tracing stage's deadlines on the device's clock (shaders/include/stage_clock.glsl):
// the trace passes stop tracing once the stage has run for T less the recent time of the passes
// after them, so a frame whose selection was predicted wrong (a camera jump that left many more
// shadow pixels uncertain) holds T with fewer pixels traced. The clock's unit is the device's (VK_KHR_shader_clock does
// not name it: nanoseconds on NVIDIA, lavapipe's own), so ticks per millisecond are learned
// from each frame's span of coverage, select and the shadow pass on it against the same
// passes' timestamps.
#pragma once
#include <algorithm>
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
  // A frame's effects pass and fill, where the deadline cut nothing.
  void learnPassTimes(double effectsMs, double fillMs) {
    effectsMs_.add(effectsMs);
    fillMs_.add(fillMs);
  }
  // A restarted selection: the passes' times were another selection's.
  void restart() {
    effectsMs_.clear();
    fillMs_.clear();
  }
  // The effects pass's deadline: T less the fill's recent time (at least kEffectsShare of T).
  // The fill is never cut: it is what makes a reduced rate's pixels worth their cost (without
  // it, 15 of 16 pixels of an item at 1/16 keep the fallback), and its time follows its pixels.
  uint32_t effectsTicks(double budgetMs) const { return ticks(std::max(budgetMs - fillMs_.value(), kEffectsShare * budgetMs)); }
  // The shadow pass's deadline: T less the effects' and the fill's recent time (at least
  // kShadowShare of T), so that shadows that ran far past their prediction (a camera jump's
  // uncertain shadow-map pixels) are cut, not the reflections and refractions after them.
  uint32_t shadowTicks(double budgetMs) const {
    return ticks(std::max(budgetMs - effectsMs_.value() - fillMs_.value(), kShadowShare * budgetMs));
  }

  // The share of T the passes keep after the deadline: the subgroups already tracing finish
  // their pixels, and the rest of the passes' invocations note what they leave out.
  static constexpr double kDrainShare = 0.03;
  static constexpr double kEffectsShare = 0.5, kShadowShare = 0.25;

 private:
  RecentMedian ticksPerMs_, effectsMs_, fillMs_;
};

}  // namespace raybudget::select
