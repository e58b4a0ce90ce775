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
  // What a frame whose fill its deadline cut would have taken with its whole fill: the fill's
  // recent time for the fill's measured one, where longer. (A cut fill ends the stage near T
  // whatever ran late before it, so taken as it is, it would teach a reserve that shrinks.)
  double stageWithWholeFill(double stageMs, double cutFillMs) const { return stageMs - cutFillMs + std::max(cutFillMs, fillMs_.value()); }
  // What a frame the stage ran teaches the deadline (selection_stage.cpp's retire).
  struct Frame {
    double budgetMs = 0.0, reserveMs = 0.0;  // its T and the reserve it ran with
    double stageMs = 0.0, effectsMs = 0.0, fillMs = 0.0;
    bool cut = false;           // the deadline left pixels to their fallbacks
    bool effectsCut = false;    // ... some of them the effects pass's
    bool fillCut = false;       // the fill's deadline left some
    bool underDeadline = true;  // its trace passes had deadlines (the clock had a rate)
  };
  // A frame teaches the passes' recent times where the deadlines cut none of their pixels (a cut
  // pass's time is a lower bound of its own), the fill's only where it ran under deadlines; a
  // frame the deadlines cut teaches the reserve. But a frame whose effects pass was cut and whose
  // stage still ended a reserve before T renews the fill's time: its fill came in shorter than
  // the time the cut left it, so the cut came from a stale fill time, not an overrun. On
  // NormalTangentMirrorTest's orbit at T = 4.65 ms a still view's fills took 1.9-2.6 ms, the
  // moving camera's after it 0.8-1.0 ms, which cut frames never taught: every frame of the
  // motion was cut, ending at 0.73-0.77 T. A fill time too long for T cuts the effects
  // pass in every frame after it, and so is never renewed, where one too long for the effects
  // pass only cuts the shadow pass early until the effects pass renews it: from a cold start
  // on NormalTangentMirrorTest (its mirror at 1/16, T = 4.6 ms) the first two frames, before
  // the clock had a rate, priced by the prior and so unbounded, filled in 6-7 ms, and every
  // frame after left the effects pass under 1 ms of T, cut, the stage ending at 0.6-0.7 T.
  // (Renewing the fill's time from the frames whose effects pass was cut as well broke that
  // loop too, but those are the frames whose selection overran, and their fills held the
  // effects pass's deadline earlier in every frame: in the benchmark's sweep, where every
  // frame runs under deadlines, 43% more pixels cut and 0.554 of the error recovered at 25%
  // of full RT against 0.612, `results/full-s64a` against `full-s63a`.)
  void learnFrame(const Frame& f);
  // A restarted selection: the passes' times and the reserve were another selection's.
  void restart() {
    effectsMs_.clear();
    fillMs_.clear();
    needed_.clear();
  }
  // The effects pass's deadline: T less the fill's time (at least kEffectsShare of T), the
  // second largest of its last 7, so that the fill's own deadline at T cuts only an outlier.
  // (With the median, half the frames whose effects pass ran to its deadline had their fill
  // cut: 30-60% of the frames of the court's and the plaza's paths at 10% of full RT.) The
  // fill is not cut with the effects pass: it is what makes a reduced rate's pixels worth their
  // cost (without it, 15 of 16 pixels of an item at 1/16 keep the fallback), and its time
  // follows its pixels.
  uint32_t effectsTicks(double budgetMs) const { return ticks(std::max(budgetMs - fillMs(), kEffectsShare * budgetMs), budgetMs); }
  // The shadow pass's deadline: T less the effects' and the fill's recent time (at least
  // kShadowShare of T), so that shadows that ran far past their prediction (a camera jump's
  // uncertain shadow-map pixels) are cut, not the reflections and refractions after them.
  uint32_t shadowTicks(double budgetMs) const {
    return ticks(std::max(budgetMs - effectsMs_.value() - fillMs(), kShadowShare * budgetMs), budgetMs);
  }
  // The fill's deadline: T itself, whatever the reserve. It cuts only a frame that would else
  // end past T: one whose passes before the fill ran past their deadlines by more than the
  // reserve, or whose fill ran past its recent time (a 4 ms fill where 0.4-0.8 ms was usual, a
  // busy moment of the machine, on the court's orbit at T = 2.45 ms). On lavapipe at T of 1-2 ms
  // such a frame's timestamps may read up to 7% past T where the clock read T (the passes'
  // launches, which the clock does not see); a reserve for it learned from the cut fills, as
  // the trace passes' is, held T + 5% no more often (court and plaza at 10% and 25% of full RT:
  // worst 0.986 against 0.989) and was dropped.
  uint32_t fillTicks(double budgetMs) const { return clockTicks(budgetMs); }

  static constexpr double kDrainShare = 0.03, kMaxReserveShare = 0.5;
  static constexpr double kEffectsShare = 0.5, kShadowShare = 0.25;

 private:
  // `ms` after the stage began in ticks (at least 1); 0, no deadline, before the clock was
  // calibrated or where it is past the clock's 32-bit span.
  uint32_t clockTicks(double ms) const;
  double fillMs() const { return fillMs_.secondLargest(); }  // the time the trace passes leave the fill

  RecentMedian ticksPerMs_, effectsMs_, fillMs_, needed_;
};

}  // namespace raybudget::select
