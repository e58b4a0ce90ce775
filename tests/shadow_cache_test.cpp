// Shadow maps are rendered when their light's casters change, not every frame: a static
// scene renders them once whatever the camera does; a moved object renders again only the
// views that see it, and the frame then equals one rendered from scratch.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

constexpr uint32_t kW = 160, kH = 96;

// The largest difference of one channel between two LDR frames, over the pixels that show
// the same object in both, other than `except`.
int maxChannelDifference(const FrameImages& a, const FrameImages& b, uint32_t except = 0xFFFFFFFEu) {
  int worst = 0;
  for (size_t p = 0; p < a.objectIds.size(); ++p) {
    if (a.objectIds[p] != b.objectIds[p] || a.objectIds[p] == except) continue;
    for (size_t c = 4 * p; c < 4 * p + 3; ++c) worst = std::max(worst, std::abs(int(a.ldrRgba8[c]) - int(b.ldrRgba8[c])));
  }
  return worst;
}

TEST(ShadowMapCache, AStaticSceneRendersItsMapsOnceAndAMovedCasterOnlyTheViewsThatSeeIt) {
  Scene scene = loadScene(test::defaultScenePath());
  // Without reflection probes: a probe whose box the sphere moves in is captured again over
  // 12 frames (reflection_probe_test), which would differ from the oracle's meanwhile.
  RenderSettings settings = test::settingsFor(Policy::None, kW, kH);
  settings.reflectionProbes = false;
  Renderer renderer(scene, settings);
  const Camera start = defaultCamera(scene, renderer.aspect());
  std::vector<FrameTiming> frames;
  for (uint32_t f = 0; f < 4; ++f)
    for (const FrameTiming& t : renderer.render(orbitCamera(start, 3 - f, 16))) frames.push_back(t);
  for (const FrameTiming& t : renderer.finish()) frames.push_back(t);
  ASSERT_EQ(frames.size(), 4u);
  // The sun, the spot and two point lights' six faces each.
  EXPECT_EQ(frames[0].shadowMapViews, 2u + 2u * 6u);
  EXPECT_GT(frames[0].shadowMapDraws, frames[0].shadowMapViews);
  for (size_t f = 1; f < frames.size(); ++f) {
    EXPECT_EQ(frames[f].shadowMapDraws, 0u) << "frame " << f << ": the camera moved, no light or caster did";
    EXPECT_FALSE(frames[f].passMs[size_t(Pass::ShadowMaps)].has_value());
    EXPECT_EQ(frames[f].skipped[size_t(Pass::ShadowMaps)], PassSkip::ShadowMapsCurrent);
  }
  const FrameImages before = renderer.readback();

  // The chrome sphere moves: its shadow moves with it in the views that see it.
  const uint32_t chrome = test::objectNamed(scene, "chrome_sphere");
  ASSERT_NE(chrome, test::kNoObjectNamed);
  const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(1.5f, 0.0f, 1.0f)) * scene.objects[chrome].transform;
  renderer.setObjectTransform(chrome, moved);
  setObjectTransform(scene, chrome, moved);
  const Camera last = orbitCamera(start, 0, 16);  // the camera of the frame before the move
  std::vector<FrameTiming> after = test::renderStill(renderer, last, 2);
  ASSERT_EQ(after.size(), 2u);
  EXPECT_GT(after[0].shadowMapViews, 0u);
  EXPECT_LT(after[0].shadowMapViews, frames[0].shadowMapViews) << "a light whose views never see the sphere keeps its map";
  EXPECT_LT(after[0].shadowMapDraws, frames[0].shadowMapDraws);
  EXPECT_EQ(after[1].shadowMapDraws, 0u);
  const FrameImages cached = renderer.readback();
  test::expectValidationClean(renderer.validationMessages());

  // The oracle: a renderer that draws every map from the moved scene (two frames, so that
  // its screen-space reflections, too, read an earlier frame from the same camera).
  Renderer fresh(scene, settings);
  test::renderStill(fresh, last, 2);
  const FrameImages reference = fresh.readback();
  test::expectValidationClean(fresh.validationMessages());
  EXPECT_LE(maxChannelDifference(cached, reference), 1) << "the maps kept or redrawn equal maps drawn from scratch";
  // The check can fail: off the sphere itself the moved sphere's shadows change the frame,
  // so maps left stale would show.
  EXPECT_GT(maxChannelDifference(before, reference, chrome), 16);
}

}  // namespace
}  // namespace raybudget
