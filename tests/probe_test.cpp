// `benefit`'s sparse probe: it traces and measures items the selection left out, shows none
// of it, and costs tiles in proportion to its share.
#include <cmath>

#include <gtest/gtest.h>

#include "shared/selection.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

// Left-out items (their bit unset in the frame's selection) that the frame measured an error for.
uint32_t measuredLeftOutItems(const std::vector<ObjectMetrics>& metrics) {
  uint32_t n = 0;
  for (const ObjectMetrics& m : metrics)
    for (uint32_t e = 0; e < RB_ITEMS_PER_OBJECT; ++e) n += !((m.selectedItems >> e) & 1u) && m.itemError[e] > 0.0f;
  return n;
}

// One frame with the probe and one without at the same selection budget (the time scale's
// prior, so the trace budget is T and the selection gets T less the probe's share): the same
// items are selected and the images are equal, while the probe adds tiles and rays and
// measures left-out items the frame without it cannot.
TEST(Probe, MeasuresLeftOutItemsAndShowsNothing) {
  const Scene scene = loadScene(test::defaultScenePath());
  RenderSettings s = test::settingsFor(Policy::Benefit, 320, 192);
  s.learnTimeScale = false;
  const Camera cam = defaultCamera(scene, 320.0f / 192.0f);
  // A budget that leaves most items out: a tenth of what the frame's candidates cost.
  s.probeShare = 0.0f;
  s.optimalBound = true;
  const test::RenderedFrames sized = test::renderFrames(scene, s, {cam}, test::kCheckSelection);
  ASSERT_GT(sized.timings.at(0).candidatesMs, 0.0);
  s.optimalBound = false;
  const float budget = float(sized.timings[0].candidatesMs / 10.0);
  s.probeShare = 0.25f;
  s.budgetMs = budget;
  const test::RenderedFrames probed = test::renderFrames(scene, s, {cam}, test::kCheckSelection);
  s.probeShare = 0.0f;
  s.budgetMs = budget - budget * 0.25f;  // the selection budget of the probed frame, as it computes it
  const test::RenderedFrames plain = test::renderFrames(scene, s, {cam}, test::kCheckSelection);
  const FrameTiming &p = probed.timings.at(0), &q = plain.timings.at(0);
  EXPECT_TRUE(p.selectionMatchesCpu.value_or(false));
  EXPECT_TRUE(p.costsMatchCpu.value_or(false)) << "the probe marks what the walk left out, at the reference's stride";
  ASSERT_GT(p.selectedObjects, 0u);
  for (size_t i = 0; i < scene.objects.size(); ++i) EXPECT_EQ(probed.metrics[i].selectedItems, plain.metrics[i].selectedItems) << "object " << i;
  EXPECT_EQ(probed.images.ldrRgba8, plain.images.ldrRgba8) << "probed pixels show their fallback";
  EXPECT_GT(p.tracedTiles, q.tracedTiles);
  EXPECT_GT(p.raysTraced, q.raysTraced);
  EXPECT_GT(measuredLeftOutItems(probed.metrics), 0u);
  EXPECT_EQ(measuredLeftOutItems(plain.metrics), 0u);
  // The probe's predicted cost is within its share: the prediction exceeds the selection's by
  // at most the probe budget.
  EXPECT_LE(p.predictedTraceMs - q.predictedTraceMs, double(budget) * 0.25 * 1.0001);
}

TEST(Probe, BadSharesAreRefusedNamingTheSetting) {
  const Scene scene = loadScene(test::defaultScenePath());
  for (float share : {-0.1f, 0.6f, std::nanf("")}) {
    RenderSettings s = test::settingsFor(Policy::Benefit, 64, 64);
    s.probeShare = share;
    test::expectRefusedNaming(scene, s, "probeShare");
  }
}

}  // namespace
}  // namespace raybudget
