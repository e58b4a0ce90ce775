#include "select/stage_deadline.h"

#include <algorithm>
#include <cmath>

namespace raybudget::select {

namespace {
// A span shorter than this is mostly the launch of its first workgroup and the readback's
// rounding, not the clock's rate.
constexpr double kShortestSpanMs = 0.05;
}  // namespace

void StageDeadline::learn(uint32_t spanTicks, double spanMs) {
  if (spanTicks == 0 || !std::isfinite(spanMs) || spanMs < kShortestSpanMs) return;
  ticksPerMs_.add(double(spanTicks) / spanMs);
}

void StageDeadline::learnFrame(const Frame& f) {
  if (!f.effectsCut && !f.fillCut) effectsMs_.add(f.effectsMs);
  // A cut effects pass stops the fill's time from being learned only where the stage overran.
  const bool overran = f.effectsCut && f.stageMs >= f.budgetMs - f.reserveMs;
  if (!f.fillCut && f.underDeadline && !overran) fillMs_.add(f.fillMs);
  if (f.cut) learnCut(f.fillCut ? stageWithWholeFill(f.stageMs, f.fillMs) : f.stageMs, f.budgetMs, f.reserveMs);
}

uint32_t StageDeadline::ticks(double atMs, double budgetMs) const {
  if (!(budgetMs > 0.0)) return 0;
  // A reserve that takes the pass's whole share leaves it its leave-outs alone: one tick.
  return clockTicks(atMs - reserveMs(budgetMs));
}

uint32_t StageDeadline::clockTicks(double ms) const {
  if (!calibrated()) return 0;
  const double t = std::max(ms * ticksPerMs(), 1.0);
  // Spans are differences of the clock's low 32 bits: half its range keeps them unambiguous.
  if (!std::isfinite(t) || t >= double(1u << 31)) return 0;
  return uint32_t(t);
}

}  // namespace raybudget::select
