// The cost model: what the selection predicts a candidate's ray tracing costs, and the time
// scale that turns that predicted work into milliseconds.
//
// Per object (on the GPU, shaders/select/select_candidates.comp; these functions are its CPU
// reference, equal bit for bit): the traversal work per traced pixel, learned from the work
// counters of the trace passes, and each candidate's predicted work and cost. Per device and
// scene (here, from the timestamps): the stage's time as an affine function of the work,
// t = t0 + scale · work, t0 the coverage and select passes plus the trace passes' own fixed
// cost, which the selection takes off the stage budget T, and one scale per cost unit (our
// work units; the paper's C).
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>

#include "raybudget/renderer.h"
#include "select/policies.h"
#include "shared/config.h"
#include "shared/selection.h"

namespace raybudget::select {

// A ray rate's code in the frame's selection (RB_RATE_*), and the share of an item's full-rate
// cost it costs where a pixel it skips costs `fill` of a traced pixel's full-rate cost
// (shared/selection.h; select_common.glsl's, rounded alike).
uint32_t rateCode(ItemRate rate);
ItemRate itemRateOfCode(uint32_t code);
float rateShare(uint32_t code, float fill);
// An item's fill share: its learned cost per skipped pixel over its full-rate cost per pixel,
// at most RB_FILL_SHARE_MAX; before either was learned the effect's prior (RB_FILL_SHARE_PRIOR,
// for shadows RB_FILL_SHARE_PRIOR_SHADOWS).
float fillShare(uint32_t effect, float fillPerPixel, float workPerPixel);
// a / b correctly rounded, as the GPU divides (select_common.glsl's exactQuotient).
float exactQuotient(float a, float b);

// How well an effect's fill keeps its benefit at 1/16 and at 1/4: shared/selection.h's q.
struct FillQuality {
  float sixteenth = 0.0f, quarter = 0.0f;
};
FillQuality fillQualities(uint32_t effect);  // the effect's prior
// A frame's qualities per effect (RB_ITEM_*; SelectPush's quarterQuality and sixteenthQuality,
// which select_common.glsl's fillQualities reads): the priors, moved toward
// RB_FILL_QUALITY_STILL after `stillFrames` frames of a still view for the effects whose
// temporal fill carries the traced values (`history`, RB_RT_* bits: each effect's is
// 1 << RB_ITEM_*, as select_common.glsl reads the frame's effects too).
static_assert(RB_RT_SHADOWS == 1u << RB_ITEM_SHADOWS && RB_RT_REFLECTIONS == 1u << RB_ITEM_REFLECTIONS &&
              RB_RT_REFRACTIONS == 1u << RB_ITEM_REFRACTIONS);
using FrameFillQualities = std::array<FillQuality, RB_ITEMS_PER_OBJECT>;
FrameFillQualities frameFillQualities(uint32_t stillFrames, uint32_t history);
FrameFillQualities priorFillQualities();  // frameFillQualities(0, 0)
// The share of each rate's skipped pixels the still frames before this one traced, for the
// reflections and refractions (0 where `history` lacks them; SelectPush's quarterQuality.w and
// sixteenthQuality.w).
struct FillStill {
  float quarter = 0.0f, sixteenth = 0.0f;
};
FillStill frameFillStill(uint32_t stillFrames, uint32_t history);
// The share of an object's reflection and refraction pixels (the larger count) that are not
// detailed (GpuCoverage::sumYHi.w; shared/selection.h's RB_FILL_DETAIL_COS): g.
float fillSmoothness(uint32_t reflectionPixels, uint32_t refractionPixels, uint32_t detailed);
// An item's fill qualities: a shadow item's the frame's, a reflection or refraction item's the
// effect's priors times g (1/4) and g^2 (1/16), moved toward RB_FILL_QUALITY_STILL by the still
// shares (select_common.glsl's itemFillQualities, bit for bit; at g = 1 the frame's).
FillQuality itemFillQuality(uint32_t effect, const FrameFillQualities& frame, FillStill still, float smoothness);
// The share of an item's full-rate value `rate` keeps at the qualities q (1 at full rate).
float keepShare(uint32_t rate, FillQuality q);

// RB_RATE_AUTO's segments of an item (shared/selection.h; select_common.glsl's rateHull,
// segmentRate, segmentCostShare, segmentValueShare): the reduced rates on the upper convex hull
// of its options (RB_HULL_* bits), how many segments it offers, and segment k's share of the
// item's full-rate cost (at fill share `fill`) and value (at its effect's fill qualities) and
// the rate (RB_RATE_*) taking it reaches.
struct RateSegment {
  float costShare = 1.0f, valueShare = 1.0f;
  uint32_t rate = 0;
};
uint32_t rateHull(float fill, FillQuality q);
uint32_t rateSegments(float fill, FillQuality q);
RateSegment rateSegment(uint32_t k, float fill, FillQuality q);

// An object's work per traced pixel after a frame that counted `work` over `pixels`: the
// mean of what it knew and the observation (the observation alone when it knew nothing,
// `previous` unchanged when the frame traced none of it).
float learnedWorkPerPixel(float previous, uint32_t work, uint32_t pixels);

// An item's work per pixel after a frame in which only the probe traced it: `previous` (or
// `prior` before one was learned) moved towards `observed` by 1/2, 1/4 or 1/8 as `pixels`
// reaches RB_PROBE_TRUSTED_PIXELS, a quarter of them, or not (select_candidates.comp's reason).
float probedWorkPerPixel(float previous, float prior, float observed, uint32_t pixels);

// A candidate's predicted work: the paper's C for `paper`; for the other policies its pixels
// times its work per pixel, or times Q and the work a ray costs (`workPerRay`,
// TimeScale::priorWorkPerRay) until that is learned.
float predictedWork(Policy policy, float paperCost, uint32_t pixels, float workPerPixel, float Q, float workPerRay);

// Items (`benefit`): an object's shadows, reflections, refractions (RB_ITEM_*), each with its
// own pixels, learned work per pixel and learned benefit b, the display error its tracing
// removed per covered pixel (shaders/select/select_candidates.comp; these are its CPU
// reference, equal bit for bit).
struct ItemLearned {
  float workPerPixel = 0.0f;
  float benefit = 0.0f;
  bool measured = false;
  float fillPerPixel = 0.0f;  // per pixel its reduced rate skipped (0: not learned)
};
// What an item knows after a frame that counted `work` and `error` (in 1/RB_ERROR_UNITS) over
// the `pixels` it was traced on (0: not traced; its benefit drifts to `prior`, the item's
// GpuObjectParams::priors).
// An item's cost per pixel is learned from its clock ticks at `workPerTick` work units per
// RB_CLOCK_UNIT ticks (the frame's: RB_WORK_PER_CLOCK_UNIT), or from its traversal work where
// nothing was timed (workPerTick 0 or no ticks). `ablation`: RB_BENEFIT_* bits (RB_BENEFIT_PRIOR_ONLY: b stays the prior).
// `probed`: the item was left out, so its counts are the probe's few tiles, which move the
// work per pixel (or, before that was learned, `priorWorkPerPixel`) by a share growing with
// the pixels probed (RB_PROBE_TRUSTED_PIXELS), not to their mean. Its cost per pixel a reduced
// rate skipped (fillPerPixel) is learned from those pixels' ticks at the same rate
// (select_candidates.comp).
struct ItemCounts {
  uint32_t work = 0, ticks = 0, error = 0, pixels = 0;
  bool probed = false;
  uint32_t rate = RB_RATE_FULL;  // the rate it was traced at (its ticks' pixels: tracedPixelCost)
  uint32_t skippedTicks = 0, skippedPixels = 0;  // of the pixels that rate skipped (their fill)
};
// The clock time of a pixel `rate` traces over full rate's per pixel (shared/selection.h's
// RB_TRACED_PIXEL_COST_*; 1 at full rate).
float tracedPixelCost(uint32_t rate);
ItemLearned learnItem(float prior, const ItemLearned& before, const ItemCounts& counts, float workPerTick, uint32_t ablation = 0,
                      float priorWorkPerPixel = 0.0f);
// An item candidate's predicted work: its pixels times its work per pixel, or before that
// is learned, the rays per pixel (a shadow ray per light; a reflection or refraction path and
// its hit's shadow rays) times the work a ray costs.
float predictedItemWork(uint32_t effect, uint32_t pixels, float workPerPixel, uint32_t lights, float workPerRay);
float priorItemWorkPerPixel(uint32_t effect, uint32_t lights, float workPerRay);
// R' = (S·I + E)·K with the hysteresis relative to E: E·(1 + S·I)·K, E = A·P·b, A the item's
// pixels over the screen's.
// pixels over the screen's (`ablation`: RB_BENEFIT_WITHOUT_CENTRALITY: P = 1,
// RB_BENEFIT_WITHOUT_HYSTERESIS: I = 0).
float itemValue(uint32_t pixels, uint32_t screenPixels, float P, float benefit, bool selectedLast, float K, float I, uint32_t ablation = 0);

// `benefit`'s sparse probe (shared/selection.h): the stride for `left`, the predicted cost of
// the candidates the walk left out, within `budget`: the least whole stride with left / stride
// <= budget, 0 (no probe) where there is nothing to probe, no budget, or more than
// RB_PROBE_MAX_STRIDE would be needed.
uint32_t probeStride(double left, double budget);
// Whether the GPU's `stride` is probeStride's for a `left` known within a relative `tolerance`.
bool probeStrideFits(uint32_t stride, double left, double budget, double tolerance);

// Predicted milliseconds: the time scale times the work.
inline float predictedCost(float msPerUnit, float work) { return msPerUnit * work; }

// Which time scale a policy's predicted work is measured in.
enum class CostUnit : uint32_t { Work = 0, PaperCost = 1, ItemWork = 2 };
CostUnit costUnitOf(Policy policy);

// The prior time scale, before any measurement: 1e-4 ms per ray (kPriorMsPerRay, 10 Mrays/s)
// of RB_PRIOR_WORK_PER_RAY work units; the paper's C is about rays per pixel of the screen, so
// per unit of C, 1e-4 ms times the pixel count.
constexpr double kPriorMsPerRay = 1e-4;
double priorMsPerUnit(CostUnit unit, uint32_t width, uint32_t height);

// What one budgeted frame measured.
struct StageMeasurement {
  double msPerUnitUsed = 0.0;  // the time scale the frame was selected with
  double work = 0.0;           // the selection's predicted work (units of the policy's cost unit)
  double traceMs = 0.0;        // the trace passes' timestamps
  double overheadMs = 0.0;     // the coverage and select passes' timestamps
  bool candidatesButNoneFit = false;
  double budgetMs = 0.0;  // the selection's budget (0: every traced frame is informative)
  uint64_t rays = 0;      // the rays the trace passes traced
  double priorWork = 0.0;  // of `work`, the part priced by the prior (items or objects never traced)
  bool scaleSettled = true;  // the scale it was selected with had TimeScale::settled's observations
  uint64_t priorRays = 0;    // the rays the items' prior counts at the pixels traced (RB_ITEM_PRIOR_RAYS)
  // The stage's deadline cut the frame and `work` still counts what it left out: its measured
  // time is a lower bound on what the whole selection costs (TimeScale::learn).
  bool cutShort = false;
  bool coverageReused = false;  // the coverage pass kept the frame before's counts (a still view)
};

// The last kSize observations of a quantity and their median (the lower middle of an even
// count): one frame's outlier (a first dispatch, the machine busy for a moment) never moves
// it, and a lasting change takes over once it fills half the window.
class RecentMedian {
 public:
  static constexpr size_t kSize = 7;
  bool empty() const { return count_ == 0; }
  size_t size() const { return std::min(count_, kSize); }
  double value() const;  // 0 when empty
  // The second largest (the largest of one or two): what all but one outlier stayed under.
  double secondLargest() const;
  void add(double x) { values_[count_++ % kSize] = x; }
  // A saved value, as if it had been observed for a whole window.
  void fill(double x) {
    values_.fill(x);
    count_ = kSize;
  }
  void scale(double factor) {
    for (double& v : values_) v *= factor;
  }
  void clear() { count_ = 0; }

 private:
  // The observations sorted, at `index` of their count (0 when empty).
  double sortedAt(size_t (*index)(size_t n)) const;

  std::array<double, kSize> values_{};
  size_t count_ = 0;
};

// The stage's time, affine in the selection's work: t = overhead + fixed + scale · work.
// overhead is the coverage and select passes (their timestamps, every frame), fixed the trace
// passes' own cost (dispatch, tile list: their timestamps in frames that traced nothing), the
// scale ms per unit of work, one per cost unit, from the frames that traced something: each
// the median of its last observations (RecentMedian). Moving averages were used before and
// dropped: one cold first frame (9 ms of coverage and select against 1.2 after) or one
// nothing-traced frame timed at seconds held the fixed cost above T for a whole benchmark
// configuration, and a scale 10x off took ten frames over budget to learn at 30% a step.
// A least-squares line through recent frames' (work, trace time) was tried for the fixed
// cost and dropped too: a budget-driven selection gives points of nearly the same work, and
// with 15% noise the fit put a true 0.5 ms anywhere in 0.2-0.9 ms, then stuck at 2.2 ms after
// the scene's cost per unit changed.
class TimeScale {
 public:
  TimeScale(uint32_t width, uint32_t height) : width_(width), height_(height) {}
  // The learned scale, or the prior before any measurement.
  double msPerUnit(CostUnit unit) const;
  // 0 where nothing was learned.
  double learned(CostUnit unit) const { return scales_[size_t(unit)].value(); }
  // Whether the scale is learned from enough frames for its errors to be noise, not the cold
  // start's bias (a saved state counts as a window).
  bool settled(CostUnit unit) const { return scales_[size_t(unit)].size() >= kSettledObservations; }
  // The coverage and select passes' recent time; `coverageReused`: in the frames whose coverage
  // pass kept the frame before's counts (a still view: its metrics alone), where any were seen.
  double overheadMs(bool coverageReused = false) const {
    return coverageReused && !overheadReused_.empty() ? overheadReused_.value() : overhead_.value();
  }
  double traceFixedMs() const { return traceFixed_.value(); }
  // The stage's fixed cost t0: overhead + the trace passes' fixed cost.
  double fixedMs(bool coverageReused = false) const { return overheadMs(coverageReused) + traceFixedMs(); }
  // How many frames the fixed cost's parts were observed in (a saved state counts as a window),
  // the coverage counted (a still view's frames, which count one in 8 (core/context.cpp),
  // would else leave a restart's cold first frame the only counted one: 3.4-5.5 ms of coverage
  // and select where 0.7-1.2 was usual, held for good once the stage left itself out).
  size_t fixedCostObservations() const { return std::min(overhead_.size(), traceFixed_.size()); }
  // The headroom the budget leaves for prediction errors: the `confidence` quantile of the
  // recent frames' measured over predicted work time over their median (the spread; the
  // bias is the scale's to learn), at least 1; 1 before kRatioWindow / 4 frames were measured.
  // The selection's budget is divided by it, so that the stage holds T in about that share of
  // frames if the errors recur. A frame whose candidates all failed to
  // fit counts as an exact prediction, so that a headroom that left nothing to trace relaxes.
  double headroom(double confidence) const;
  // Before an item or object was traced, its work per ray in `unit`: the recent frames' trace
  // time per counted ray (kPriorMsPerRay before any) over the unit's scale. A constant in work
  // units was 10x the learned costs under a calibrated scale: too dear for the probe to run,
  // so a restarted configuration never learned its items' costs. Objects count the rays
  // traced; items the rays their prior prices per traced pixel (a light's shadow ray, a path
  // and the shadow rays of its hit), so that the classifier's shadow-map taps, which trace few
  // rays, price items at what they cost per prior ray: counted as traced rays, a frame with a
  // shadow item made every ray 1.6x dearer and left Suzanne's mirror unpriced at a budget
  // that bought it.
  double priorWorkPerRay(CostUnit unit) const { return msPerRay(unit) / msPerUnit(unit); }
  double msPerRay(CostUnit unit) const {
    const RecentMedian& m = msPerRay_[rayKind(unit)];
    return m.empty() ? kPriorMsPerRay : m.value();
  }
  double learnedMsPerRay(CostUnit unit) const { return msPerRay_[rayKind(unit)].value(); }  // 0 where nothing was learned
  // A saved state (zeros: the prior, no fixed cost), without the recent errors behind the
  // headroom. Values are the caller's to validate.
  void set(const CostModel& saved);
  CostModel saved() const;  // what set() restores: the learned values, 0 where nothing was learned
  // Forgets the recent errors (a restarted selection's headroom must not depend on what ran
  // before it).
  void forgetErrors() { ratioCount_ = 0; }
  void recordError(double measuredOverPredicted) { ratios_[ratioCount_++ % kRatioWindow] = measuredOverPredicted; }
  void learn(CostUnit unit, const StageMeasurement& m);

 private:
  uint32_t width_, height_;
  std::array<RecentMedian, 3> scales_;  // per cost unit
  RecentMedian overhead_, overheadReused_, traceFixed_;
  std::array<RecentMedian, 2> msPerRay_;  // per ray traced (objects), per prior ray (items)
  static size_t rayKind(CostUnit unit) { return unit == CostUnit::ItemWork ? 1 : 0; }
  static constexpr size_t kRatioWindow = 32;
  static constexpr size_t kSettledObservations = 3;
  static constexpr double kInformativeShare = 0.25;
  // A frame whose predicted work is more than this share priced by the prior does not teach
  // the headroom (cost_model.cpp's learn says why).
  static constexpr double kPriorPricedShare = 0.25;
  std::array<double, kRatioWindow> ratios_{};  // the last frames' measured / predicted work time
  size_t ratioCount_ = 0;
};

}  // namespace raybudget::select
