// The cost model's CPU half: the per-object arithmetic the GPU reproduces bit for bit (the
// frame test in rt_effects_test.cpp compares them), and the time scale learned from
// timestamps.
#include <gtest/gtest.h>

#include "select/cost_model.h"
#include "shared/selection.h"

namespace raybudget {
namespace {

using select::CostUnit;
using select::Policy;

TEST(CostModel, WorkPerPixelStartsFromTheFirstObservationThenAveragesWithEach) {
  EXPECT_EQ(select::learnedWorkPerPixel(0.0f, 300, 10), 30.0f);
  EXPECT_EQ(select::learnedWorkPerPixel(30.0f, 500, 10), 40.0f);
  EXPECT_EQ(select::learnedWorkPerPixel(30.0f, 0, 10), 30.0f) << "counted nothing: unchanged";
  EXPECT_EQ(select::learnedWorkPerPixel(30.0f, 500, 0), 30.0f) << "traced no pixel: unchanged";
  // Correctly rounded: 1/3 as the nearest float, as the GPU's double quotient gives it.
  EXPECT_EQ(select::learnedWorkPerPixel(0.0f, 1, 3), float(1.0 / 3.0));
}

TEST(CostModel, PredictedWorkIsPixelsTimesWorkPerPixelOrQTimesThePriorAndPaperUsesC) {
  EXPECT_EQ(select::predictedWork(Policy::Density, 7.0f, 100, 0.0f, 2.0f), 100.0f * 2.0f * float(RB_PRIOR_WORK_PER_RAY));
  EXPECT_EQ(select::predictedWork(Policy::Nearest, 7.0f, 100, 12.5f, 2.0f), 1250.0f);
  EXPECT_EQ(select::predictedWork(Policy::Paper, 7.0f, 100, 12.5f, 2.0f), 7.0f);
  EXPECT_EQ(select::predictedCost(0.5f, 1250.0f), 625.0f);
}

TEST(CostModel, TimeScaleStartsAtThePriorAndMovesPartWayTowardsWhatWasMeasured) {
  select::TimeScale k(640, 360);
  const double prior = select::priorMsPerUnit(CostUnit::Work, 640, 360);
  EXPECT_EQ(k.msPerUnit(CostUnit::Work), prior);
  EXPECT_EQ(k.learned(CostUnit::Work), 0.0);
  EXPECT_EQ(k.fixedMs(), 0.0);
  EXPECT_DOUBLE_EQ(k.msPerUnit(CostUnit::PaperCost), 1e-4 * 640 * 360);
  // Predicted 2 ms of work, measured 3 (no fixed cost known): 30% of the way to 1.5x.
  k.learn(CostUnit::Work, {prior, 2.0 / prior, 3.0, 0.4, false});
  EXPECT_DOUBLE_EQ(k.msPerUnit(CostUnit::Work), prior * (0.7 + 0.3 * 1.5));
  EXPECT_DOUBLE_EQ(k.overheadMs(), 0.4);
  EXPECT_EQ(k.learned(CostUnit::PaperCost), 0.0) << "the other unit keeps its prior";
  // A 10x outlier moves it by at most 2x of the scale it was selected with.
  const double before = k.msPerUnit(CostUnit::Work);
  k.learn(CostUnit::Work, {before, 1.0 / before, 10.0, 0.2, false});
  EXPECT_DOUBLE_EQ(k.msPerUnit(CostUnit::Work), 0.7 * before + 0.3 * 2.0 * before);
  EXPECT_DOUBLE_EQ(k.overheadMs(), 0.7 * 0.4 + 0.3 * 0.2);
  // Nothing traced to measure: unchanged; candidates none of which fit: relaxed by 10%.
  const double now = k.msPerUnit(CostUnit::Work);
  k.learn(CostUnit::Work, {now, 0.0, 0.1, 0.2, false});
  EXPECT_EQ(k.msPerUnit(CostUnit::Work), now);
  k.learn(CostUnit::Work, {now, 0.0, 0.1, 0.2, true});
  EXPECT_DOUBLE_EQ(k.msPerUnit(CostUnit::Work), 0.9 * now);
  // A saved model restores exactly; zeros mean the prior.
  k.set(0.0, 2.5, 0.1, 0.3);
  EXPECT_EQ(k.msPerUnit(CostUnit::Work), prior);
  EXPECT_EQ(k.msPerUnit(CostUnit::PaperCost), 2.5);
  EXPECT_EQ(k.overheadMs(), 0.1);
  EXPECT_EQ(k.traceFixedMs(), 0.3);
  EXPECT_DOUBLE_EQ(k.fixedMs(), 0.4);
}

// Frames that traced nothing time the trace passes' fixed cost (their dispatches over an
// empty tile list); the scale then fits what the work adds beyond it.
TEST(CostModel, FramesThatTraceNothingGiveTheFixedCostAndTheScaleFitsTheRest) {
  const double fixed = 0.5, scale = 5e-6;  // the prior is 3.1e-6 ms per unit
  select::TimeScale k(640, 360);
  for (int f = 0; f < 30; ++f) k.learn(CostUnit::Work, {k.msPerUnit(CostUnit::Work), 0.0, fixed, 0.2, false});
  EXPECT_NEAR(k.traceFixedMs(), fixed, 1e-4);
  EXPECT_EQ(k.learned(CostUnit::Work), 0.0) << "nothing traced: the scale keeps its prior";
  EXPECT_NEAR(k.fixedMs(), 0.7, 1e-4);
  for (int f = 0; f < 60; ++f) {
    const double work = 1e5 * (1 + f % 5);  // 0.5 to 2.5 ms of work
    k.learn(CostUnit::Work, {k.msPerUnit(CostUnit::Work), work, fixed + scale * work, 0.2, false});
  }
  EXPECT_NEAR(k.msPerUnit(CostUnit::Work), scale, 1e-3 * scale);
  EXPECT_NEAR(k.traceFixedMs(), fixed, 1e-4) << "frames that traced something leave the fixed cost";
}

}  // namespace
}  // namespace raybudget
