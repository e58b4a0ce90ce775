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
  // `atMs` after the stage began, less the reserve for what runs past a deadline under T, in
  // device-clock ticks; 0, no deadline, before the clock was calibrated or where T is past the
  // clock's 32-bit span.
  uint32_t ticks(double atMs, double budgetMs) const;
  // What the stage runs past a deadline: the subgroups under way finish their pixels, the rest
  // of the pass's invocations note what they leave out, the passes after it run. The reserve
  // each frame the deadline cut needed to end at T (the one it had and its time past T) is
  // learned as their recent median, within [kDrainShare, kMaxReserveShare] of T (kDrainShare
  // until a frame was cut): the leave-outs of a pass over most of the screen cost 0.5-3 ms on
  // lavapipe, which a fixed 3% of T left `paper` over T in most of its cut frames, and 20%
  // left `benefit-rates` 0.7 ms over T = 2.4 ms on AlphaBlendModeTest (one run, the machine busy).
  double reserveMs(double budgetMs) const {
    const double least = kDrainShare * budgetMs;
    return needed_.empty() ? least : std::clamp(needed_.value(), least, kMaxReserveShare * budgetMs);
  }
  void learnCut(double stageMs, double budgetMs, double reserveMs) { needed_.add(reserveMs + stageMs - budgetMs); }
  // A frame's effects pass and fill, where the deadline cut none of the effects pass's pixels
  // (the fill is never cut, but where the effects pass was, it finds fewer traced neighbours).
  void learnPassTimes(double effectsMs, double fillMs) {
    effectsMs_.add(effectsMs);
    fillMs_.add(fillMs);
  }
  // A restarted selection: the passes' times and the reserve were another selection's.
  void restart() {
    effectsMs_.clear();
    fillMs_.clear();
    needed_.clear();
  }
  // The effects pass's deadline: T less the fill's recent time (at least kEffectsShare of T).
  // The fill is never cut: it is what makes a reduced rate's pixels worth their cost (without
  // it, 15 of 16 pixels of an item at 1/16 keep the fallback), and its time follows its pixels.
  uint32_t effectsTicks(double budgetMs) const {
    return ticks(std::max(budgetMs - fillMs_.value(), kEffectsShare * budgetMs), budgetMs);
  }
  // The shadow pass's deadline: T less the effects' and the fill's recent time (at least
  // kShadowShare of T), so that shadows that ran far past their prediction (a camera jump's
  // uncertain shadow-map pixels) are cut, not the reflections and refractions after them.
  uint32_t shadowTicks(double budgetMs) const {
    return ticks(std::max(budgetMs - effectsMs_.value() - fillMs_.value(), kShadowShare * budgetMs), budgetMs);
  }

  static constexpr double kDrainShare = 0.03, kMaxReserveShare = 0.5;
  static constexpr double kEffectsShare = 0.5, kShadowShare = 0.25;

 private:
  RecentMedian ticksPerMs_, effectsMs_, fillMs_, needed_;
};

}  // namespace raybudget::select
