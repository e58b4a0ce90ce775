#include "select/cost_model.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "shared/selection.h"

namespace raybudget::select {

float exactQuotient(float a, float b) { return float(double(a) / double(b)); }

namespace {
// A learned per-pixel figure after an observation: the mean of the two, or the observation
// alone when nothing was learned yet (0).
float averagedWith(float previous, float observed) { return previous > 0.0f ? 0.5f * (previous + observed) : observed; }
}  // namespace

float probedWorkPerPixel(float previous, float prior, float observed, uint32_t pixels) {
  const float from = previous > 0.0f ? previous : prior;
  const float share = pixels >= RB_PROBE_TRUSTED_PIXELS ? 0.5f : pixels >= RB_PROBE_TRUSTED_PIXELS / 4u ? 0.25f : 0.125f;
  return from + (observed - from) * share;
}

float learnedWorkPerPixel(float previous, uint32_t work, uint32_t pixels) {
  if (pixels == 0 || work == 0) return previous;
  return averagedWith(previous, exactQuotient(float(work), float(pixels)));
}

float predictedWork(Policy policy, float paperCost, uint32_t pixels, float workPerPixel, float Q, float workPerRay) {
  if (policy == Policy::Paper) return paperCost;
  const float perPixel = workPerPixel > 0.0f ? workPerPixel : Q * workPerRay;
  return float(pixels) * perPixel;
}

uint32_t rateCode(ItemRate rate) {
  switch (rate) {
    case ItemRate::Half: return RB_RATE_HALF;
    case ItemRate::Quarter: return RB_RATE_QUARTER;
    case ItemRate::Sixteenth: return RB_RATE_SIXTEENTH;
    case ItemRate::Auto: return RB_RATE_AUTO;
    case ItemRate::Full: break;
  }
  return RB_RATE_FULL;
}

ItemRate itemRateOfCode(uint32_t code) {
  switch (code) {
    case RB_RATE_HALF: return ItemRate::Half;
    case RB_RATE_QUARTER: return ItemRate::Quarter;
    case RB_RATE_SIXTEENTH: return ItemRate::Sixteenth;
    default: return ItemRate::Full;
  }
}

float rateShare(uint32_t code, float fill) {
  if (code != RB_RATE_HALF && code != RB_RATE_QUARTER && code != RB_RATE_SIXTEENTH) return 1.0f;
  // Two roundings, as the GPU's precise product and sum (no fused multiply-add: -ffp-contract=off).
  const float skipped = (code == RB_RATE_HALF ? 0.5f : code == RB_RATE_QUARTER ? 0.75f : 0.9375f) * fill;
  const float traced = float(code == RB_RATE_HALF ? RB_TRACED_SHARE_HALF : code == RB_RATE_QUARTER ? RB_TRACED_SHARE_QUARTER : RB_TRACED_SHARE_SIXTEENTH);
  return traced + skipped;
}

float fillShare(uint32_t effect, float fillPerPixel, float workPerPixel) {
  if (fillPerPixel > 0.0f && workPerPixel > 0.0f) return std::min(exactQuotient(fillPerPixel, workPerPixel), float(RB_FILL_SHARE_MAX));
  return float(effect == RB_ITEM_SHADOWS ? RB_FILL_SHARE_PRIOR_SHADOWS : RB_FILL_SHARE_PRIOR);
}

FillQuality fillQualities(uint32_t effect) {
  const bool shadows = effect == RB_ITEM_SHADOWS, reflections = effect == RB_ITEM_REFLECTIONS;
  FillQuality q;
  q.sixteenth = float(shadows       ? RB_FILL_QUALITY_SIXTEENTH_SHADOWS
                      : reflections ? RB_FILL_QUALITY_SIXTEENTH_REFLECTIONS
                                    : RB_FILL_QUALITY_SIXTEENTH_REFRACTIONS);
  q.quarter = float(shadows ? RB_FILL_QUALITY_QUARTER_SHADOWS : reflections ? RB_FILL_QUALITY_QUARTER_REFLECTIONS : RB_FILL_QUALITY_QUARTER_REFRACTIONS);
  return q;
}

namespace {
// The share of each rate's skipped pixels the still frames before this one traced.
FillStill stillShares(uint32_t stillFrames) {
  auto traced = [&](uint32_t period) { return std::min(1.0f, float(stillFrames) / float(period - 1)); };
  return {traced(RB_RATE_PERIOD(RB_RATE_QUARTER)), traced(RB_RATE_PERIOD(RB_RATE_SIXTEENTH))};
}
// A quality moved toward RB_FILL_QUALITY_STILL by `share` (one rounding per operation, as the
// GPU's precise ones).
float towardStill(float quality, float share) { return quality + (float(RB_FILL_QUALITY_STILL) - quality) * share; }
}  // namespace

FrameFillQualities frameFillQualities(uint32_t stillFrames, uint32_t history) {
  FrameFillQualities q;
  const FillStill shares = stillShares(stillFrames);
  for (uint32_t e = 0; e < RB_ITEMS_PER_OBJECT; ++e) {
    q[e] = fillQualities(e);
    if (!((history >> e) & 1u)) continue;
    q[e] = {towardStill(q[e].sixteenth, shares.sixteenth), towardStill(q[e].quarter, shares.quarter)};
  }
  return q;
}

FrameFillQualities priorFillQualities() { return frameFillQualities(0, 0); }

FillStill frameFillStill(uint32_t stillFrames, uint32_t history) { return history & RB_RT_REFLECTIONS ? stillShares(stillFrames) : FillStill{}; }

float fillSmoothness(uint32_t reflectionPixels, uint32_t refractionPixels, uint32_t detailed) {
  const uint32_t pixels = std::max(reflectionPixels, refractionPixels);
  return pixels == 0 ? 1.0f : exactQuotient(float(pixels - std::min(detailed, pixels)), float(pixels));
}

FillQuality itemFillQuality(uint32_t effect, const FrameFillQualities& frame, FillStill still, float smoothness) {
  if (effect == RB_ITEM_SHADOWS) return frame[effect];
  const FillQuality prior = fillQualities(effect);
  const float g2 = smoothness * smoothness;
  return {towardStill(prior.sixteenth * g2, still.sixteenth), towardStill(prior.quarter * smoothness, still.quarter)};
}

float keepShare(uint32_t rate, FillQuality q) {
  if (rate != RB_RATE_QUARTER && rate != RB_RATE_SIXTEENTH) return 1.0f;
  // Two roundings, as the GPU's precise product and sum.
  const float filled = rate == RB_RATE_QUARTER ? 0.75f * q.quarter : 0.9375f * q.sixteenth;
  return (rate == RB_RATE_QUARTER ? 0.25f : 0.0625f) + filled;
}

namespace {
struct Option {
  float cost, value;
};
// Whether option b lies strictly above the line from a to c (select_common.glsl's aboveChord).
bool aboveChord(Option a, Option b, Option c) { return (b.value - a.value) * (c.cost - a.cost) > (c.value - a.value) * (b.cost - a.cost); }
}  // namespace

uint32_t rateHull(float fill, FillQuality q) {
  const Option skip{0.0f, 0.0f}, full{1.0f, 1.0f};
  const Option sixteenth{rateShare(RB_RATE_SIXTEENTH, fill), keepShare(RB_RATE_SIXTEENTH, q)};
  const Option quarter{rateShare(RB_RATE_QUARTER, fill), keepShare(RB_RATE_QUARTER, q)};
  bool onSixteenth = aboveChord(skip, sixteenth, quarter);
  const bool onQuarter = aboveChord(onSixteenth ? sixteenth : skip, quarter, full);
  if (!onQuarter && onSixteenth) onSixteenth = aboveChord(skip, sixteenth, full);
  return (onSixteenth ? RB_HULL_SIXTEENTH : 0u) | (onQuarter ? RB_HULL_QUARTER : 0u);
}

uint32_t rateSegments(float fill, FillQuality q) { return 1u + uint32_t(std::popcount(rateHull(fill, q))); }

namespace {
// The rate segment k of an item with the rates `hull` reaches (select_common.glsl's segmentRate).
uint32_t segmentRate(uint32_t k, uint32_t hull) {
  if (hull & RB_HULL_SIXTEENTH) {
    if (k == 0) return RB_RATE_SIXTEENTH;
    --k;
  }
  return (hull & RB_HULL_QUARTER) && k == 0 ? RB_RATE_QUARTER : RB_RATE_FULL;
}
}  // namespace

RateSegment rateSegment(uint32_t k, float fill, FillQuality q) {
  const uint32_t hull = rateHull(fill, q);
  const uint32_t rate = segmentRate(k, hull), from = k == 0 ? 0u : segmentRate(k - 1, hull);
  const float costFrom = k == 0 ? 0.0f : rateShare(from, fill), valueFrom = k == 0 ? 0.0f : keepShare(from, q);
  return {rateShare(rate, fill) - costFrom, keepShare(rate, q) - valueFrom, rate};
}

float tracedPixelCost(uint32_t rate) { return float(RB_TRACED_PIXEL_COST(rate)); }

ItemLearned learnItem(float prior, const ItemLearned& before, const ItemCounts& counts, float workPerTick, uint32_t ablation,
                      float priorWorkPerPixel) {
  ItemLearned after = before;
  const bool learnBenefit = !(ablation & RB_BENEFIT_PRIOR_ONLY);
  const uint32_t pixels = counts.pixels;
  if (pixels > 0) {
    const bool timed = workPerTick > 0.0f && counts.ticks > 0;
    if (timed || counts.work > 0) {
      const float observed = timed ? exactQuotient(exactQuotient(float(counts.ticks), float(pixels)) * workPerTick, tracedPixelCost(counts.rate))
                                   : exactQuotient(float(counts.work), float(pixels));
      after.workPerPixel = counts.probed ? probedWorkPerPixel(before.workPerPixel, priorWorkPerPixel, observed, pixels)
                                         : averagedWith(before.workPerPixel, observed);
    }
    if (learnBenefit) {
      const float removed = exactQuotient(float(counts.error), float(pixels) * float(RB_ERROR_UNITS));
      after.benefit = before.measured ? 0.5f * (before.benefit + removed) : removed;
      after.measured = true;
    }
  }
  if (counts.skippedPixels > 0 && workPerTick > 0.0f && counts.skippedTicks > 0)
    after.fillPerPixel = averagedWith(before.fillPerPixel, exactQuotient(float(counts.skippedTicks), float(counts.skippedPixels)) * workPerTick);
  if (pixels == 0 || !learnBenefit) {
    // The drift's product is exact (a power-of-two share), so a fused multiply-add rounds alike.
    after.benefit = before.measured ? before.benefit + (prior - before.benefit) * float(RB_BENEFIT_DRIFT) : prior;
  }
  return after;
}

float priorItemWorkPerPixel(uint32_t effect, uint32_t lights, float workPerRay) {
  const float rays = float(RB_ITEM_PRIOR_RAYS(lights, effect));
  return rays * workPerRay;
}

float predictedItemWork(uint32_t effect, uint32_t pixels, float workPerPixel, uint32_t lights, float workPerRay) {
  const float perPixel = workPerPixel > 0.0f ? workPerPixel : priorItemWorkPerPixel(effect, lights, workPerRay);
  return float(pixels) * perPixel;
}

float itemValue(uint32_t pixels, uint32_t screenPixels, float P, float benefit, bool selectedLast, float K, float I, uint32_t ablation) {
  const float A = exactQuotient(float(pixels), float(screenPixels));
  const float E = A * (ablation & RB_BENEFIT_WITHOUT_CENTRALITY ? 1.0f : P) * benefit;
  const float hysteresis = 1.0f + (selectedLast ? 1.0f : 0.0f) * (ablation & RB_BENEFIT_WITHOUT_HYSTERESIS ? 0.0f : I);
  return E * hysteresis * K;
}

CostUnit costUnitOf(Policy policy) {
  if (policy == Policy::Paper) return CostUnit::PaperCost;
  return policy == Policy::Benefit ? CostUnit::ItemWork : CostUnit::Work;
}

double priorMsPerUnit(CostUnit unit, uint32_t width, uint32_t height) {
  return unit == CostUnit::PaperCost ? kPriorMsPerRay * double(width) * double(height) : kPriorMsPerRay / RB_PRIOR_WORK_PER_RAY;
}

double RecentMedian::sortedAt(size_t (*index)(size_t n)) const {
  const size_t n = size();
  if (n == 0) return 0.0;
  std::array<double, kSize> sorted = values_;
  std::sort(sorted.begin(), sorted.begin() + n);
  return sorted[index(n)];
}

double RecentMedian::value() const {
  return sortedAt([](size_t n) { return (n - 1) / 2; });
}

double RecentMedian::secondLargest() const {
  return sortedAt([](size_t n) { return n >= 3 ? n - 2 : n - 1; });
}

double TimeScale::msPerUnit(CostUnit unit) const {
  const RecentMedian& k = scales_[size_t(unit)];
  return k.empty() ? priorMsPerUnit(unit, width_, height_) : k.value();
}

void TimeScale::set(const CostModel& m) {
  auto restore = [](RecentMedian& median, double x) { x > 0.0 ? median.fill(x) : median.clear(); };
  restore(scales_[size_t(CostUnit::Work)], m.msPerWorkUnit);
  restore(scales_[size_t(CostUnit::PaperCost)], m.msPerPaperCost);
  restore(scales_[size_t(CostUnit::ItemWork)], m.msPerItemWorkUnit);
  restore(overhead_, m.stageOverheadMs);
  overheadReused_.clear();  // (not saved: learned again from the first still frames)
  restore(traceFixed_, m.traceFixedMs);
  restore(msPerRay_[rayKind(CostUnit::Work)], m.msPerRay);
  restore(msPerRay_[rayKind(CostUnit::ItemWork)], m.msPerItemRay);
  forgetErrors();
}

CostModel TimeScale::saved() const {
  return {learned(CostUnit::Work), learned(CostUnit::PaperCost), learned(CostUnit::ItemWork), overheadMs(), traceFixedMs(),
          learnedMsPerRay(CostUnit::Work), learnedMsPerRay(CostUnit::ItemWork)};
}

// The scale observed is (trace - fixed) / work, kept within 1/16-16x of the scale the frame
// was selected with (a trace time under the fixed cost says nothing of the scale); the
// timestamps arrive two frames late, which the median's window spans. Only frames whose
// predicted or measured work time is at least kInformativeShare of their budget teach the
// scale and the headroom: a frame that traced the probe's few tiles alone (0.2 ms predicted
// at T = 10 ms) times mostly the fixed cost's jitter and the per-tile cost, and read as
// scales 5-20x off it held the headroom at 8-14x for 40 frames, so that only such frames
// followed.
void TimeScale::learn(CostUnit unit, const StageMeasurement& m) {
  (m.coverageReused ? overheadReused_ : overhead_).add(m.overheadMs);
  RecentMedian& k = scales_[size_t(unit)];
  const double used = m.msPerUnitUsed;
  if (m.work * used <= 1e-3) {  // nothing traced: the trace passes' time is their fixed cost
    traceFixed_.add(m.traceMs);
    if (m.candidatesButNoneFit) {  // nothing to measure: let the model relax
      k.empty() ? k.add(0.9 * msPerUnit(unit)) : k.scale(0.9);
      recordError(1.0);  // and the headroom, which would else stay
    }
    return;
  }
  const double excess = m.traceMs - traceFixedMs();
  if (std::max(m.work * used, excess) < kInformativeShare * m.budgetMs) return;
  const uint64_t rays = unit == CostUnit::ItemWork ? m.priorRays : m.rays;  // (msPerRay_, per kind)
  if (rays > 0 && excess > 0.0) msPerRay_[rayKind(unit)].add(excess / double(rays));
  // A frame cut short traced less than its work: its scale is at least the one it was selected
  // with. Left out, the frames that fitted T would be the only ones learned from, a censored
  // sample whose median stays below the cost of the frames the deadline cuts; on the court's
  // orbit `paper` was cut in 43 of 45 frames.
  const double scale = m.cutShort ? std::max(excess / m.work, used) : excess / m.work;
  // The prior's error is a bias the first traced frame of each item removes, not the noise the
  // headroom is for: from a restart, two such frames (3x and 6x their prediction) were the
  // 0.9 quantile that divided the budget by 2.9 on Suzanne's orbit, so the mirror that fitted
  // T was left out for good. (The scale still learns from them: its median outvotes them, and
  // a selection that keeps taking untraced objects, as density's can on an orbit, would else
  // never learn it.)
  // So is the error of a scale learned from fewer than three frames: on CesiumMilkTruck from
  // a cold start the frames selected with the prior scale, then with one learned from a
  // prior-priced frame, ran 12x and 4x over; among the first eight they divided the budget by
  // 3.3 and left the truck, which fitted T twice over, out.
  if (m.scaleSettled && m.priorWork <= kPriorPricedShare * m.work) recordError(scale / used);
  k.add(std::clamp(scale, used / 16.0, 16.0 * used));
}

double TimeScale::headroom(double confidence) const {
  const size_t n = std::min(ratioCount_, kRatioWindow);
  if (n < kRatioWindow / 4) return 1.0;
  std::array<double, kRatioWindow> sorted = ratios_;
  std::sort(sorted.begin(), sorted.begin() + n);
  // Relative to the median: a bias the scale is still learning away (the first frames, from
  // the prior) is not noise, and would otherwise hold the budget down for a whole window.
  // The index within n - 1: a lone outlier (a cold first dispatch) is never the 0.9 quantile.
  const size_t at = size_t(confidence * double(n - 1));
  return std::max(1.0, sorted[at] / sorted[n / 2]);
}

uint32_t probeStride(double left, double budget) {
  if (!(left > 0.0) || !(budget > 0.0)) return 0;
  const double ratio = std::ceil(left / budget);
  return ratio <= double(RB_PROBE_MAX_STRIDE) ? std::max<uint32_t>(uint32_t(ratio), 1u) : 0u;
}

bool probeStrideFits(uint32_t stride, double left, double budget, double tolerance) {
  return stride == probeStride(left * (1.0 - tolerance), budget) || stride == probeStride(left * (1.0 + tolerance), budget);
}

}  // namespace raybudget::select
