// Shadow rays that end past the shadow map's nearest blocker (RayTracingSettings::
// shortenShadowRays): on the default scene, which has a directional, a spot and two point
// lights, they do less traversal work than rays that run to the light and give the same image.
// Every lit pixel traces its shadows (classifier off), so the figure does not depend on
// which pixels the classifier finds uncertain.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

uint64_t shadowWork(const std::vector<ObjectMetrics>& metrics) {
  uint64_t work = 0;
  for (const ObjectMetrics& m : metrics) work += m.itemWork[0];
  return work;
}

TEST(ShadowRayEnd, SavesTraversalAndKeepsTheImage) {
  const Scene scene = loadScene(test::defaultScenePath());
  RenderSettings s = test::settingsFor(Policy::Classified, 320, 192);
  s.rayTracing.reflections = false;
  s.rayTracing.refractions = false;
  s.rayTracing.classifyShadows = false;
  const Camera cam = defaultCamera(scene, 320.0f / 192.0f);
  const test::RenderedFrames shortened = test::renderFrames(scene, s, {cam});
  s.rayTracing.shortenShadowRays = false;
  const test::RenderedFrames full = test::renderFrames(scene, s, {cam});

  const uint64_t workShort = shadowWork(shortened.metrics), workFull = shadowWork(full.metrics);
  size_t differing = 0, largest = 0;
  const size_t pixels = full.images.ldrRgba8.size() / 4;
  for (size_t p = 0; p < pixels; ++p) {
    size_t d = 0;
    for (int c = 0; c < 3; ++c) d = std::max<size_t>(d, size_t(std::abs(int(shortened.images.ldrRgba8[p * 4 + c]) - int(full.images.ldrRgba8[p * 4 + c]))));
    differing += d > 1 ? 1 : 0;
    largest = std::max(largest, d);
  }
  std::printf("shadow work: %llu shortened, %llu to the light (%.3f); pixels differing by more than 1/255: %zu of %zu (largest %zu)\n",
              (unsigned long long)workShort, (unsigned long long)workFull, double(workShort) / double(workFull), differing, pixels, largest);
  ASSERT_GT(workFull, 0u);
  EXPECT_LT(double(workShort), 0.9 * double(workFull)) << "ending at the map's blocker saves traversal";
  EXPECT_LE(differing, pixels / 1000) << "the shortened rays find the blockers the full ones find";
}

}  // namespace
}  // namespace raybudget
