#include "select/cost_model.h"

#include <algorithm>

#include "shared/selection.h"

namespace raybudget::select {

float learnedWorkPerPixel(float previous, uint32_t work, uint32_t pixels) {
  if (pixels == 0 || work == 0) return previous;
  // Correctly rounded, as the GPU computes it in double (select_common.glsl's exactQuotient).
  const float observed = float(double(float(work)) / double(float(pixels)));
  return previous > 0.0f ? 0.5f * (previous + observed) : observed;
}

float predictedWork(Policy policy, float paperCost, uint32_t pixels, float workPerPixel, float Q) {
  if (policy == Policy::Paper) return paperCost;
  const float perPixel = workPerPixel > 0.0f ? workPerPixel : Q * float(RB_PRIOR_WORK_PER_RAY);
  return float(pixels) * perPixel;
}

CostUnit costUnitOf(Policy policy) { return policy == Policy::Paper ? CostUnit::PaperCost : CostUnit::Work; }

double priorMsPerUnit(CostUnit unit, uint32_t width, uint32_t height) {
  return unit == CostUnit::PaperCost ? 1e-4 * double(width) * double(height) : 1e-4 / RB_PRIOR_WORK_PER_RAY;
}

double TimeScale::msPerUnit(CostUnit unit) const {
  const double k = learned_[size_t(unit)];
  return k > 0.0 ? k : priorMsPerUnit(unit, width_, height_);
}

void TimeScale::set(double msPerWorkUnit, double msPerPaperCost, double overheadMs) {
  learned_ = {msPerWorkUnit, msPerPaperCost};
  overheadMs_ = overheadMs;
}

void TimeScale::learn(CostUnit unit, const StageMeasurement& m) {
  overheadMs_ = overheadMs_ > 0.0 ? 0.7 * overheadMs_ + 0.3 * m.overheadMs : m.overheadMs;
  const double current = msPerUnit(unit);
  if (m.predictedTraceMs > 1e-3 && m.measuredTraceMs > 1e-3) {
    const double observed = m.msPerUnitUsed * std::clamp(m.measuredTraceMs / m.predictedTraceMs, 0.5, 2.0);
    learned_[size_t(unit)] = 0.7 * current + 0.3 * observed;
  } else if (m.candidatesButNoneFit) {
    learned_[size_t(unit)] = current * 0.9;  // nothing to measure, so let the model relax
  }
}

}  // namespace raybudget::select
