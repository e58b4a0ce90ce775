// Shadow maps are rendered when their light's casters change or their size does, not every
// frame: a static scene renders them once while the camera keeps each map's size; a moved
// object renders again only the views that see it, and the frame then equals one rendered
// from scratch. Spot and point lights' maps take the size their reach covers on screen.
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "passes/shadow_maps.h"

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

// The share of the pixels showing an object in `reference` where a channel of `image` differs
// by more than 16/255.
double shareDifferingBeyond16(const FrameImages& image, const FrameImages& reference) {
  size_t differing = 0, covered = 0;
  for (size_t p = 0; p < reference.objectIds.size(); ++p) {
    if (reference.objectIds[p] == 0xFFFFFFFFu) continue;
    ++covered;
    for (size_t c = 4 * p; c < 4 * p + 3; ++c)
      if (std::abs(int(image.ldrRgba8[c]) - int(reference.ldrRgba8[c])) > 16) {
        ++differing;
        break;
      }
  }
  EXPECT_GT(covered, 0u);
  return covered ? double(differing) / double(covered) : 1.0;
}

TEST(ShadowMapCache, AStaticSceneRendersItsMapsOnceAndAMovedCasterOnlyTheViewsThatSeeIt) {
  Scene scene = loadScene(test::defaultScenePath());
  // Without reflection probes: a probe whose box the sphere moves in is captured again over
  // 12 frames (reflection_probe_test), which would differ from the oracle's meanwhile. Maps at
  // full size: the orbit changes the size some maps need (ShadowMapFit below).
  RenderSettings settings = test::settingsFor(Policy::None, kW, kH);
  settings.reflectionProbes = false;
  settings.shadowMapsFitScreen = false;
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


// A sphere of radius 1 straight ahead of a camera at the origin looking down -z, with a
// focal length of 500 pixels.
TEST(ShadowMapFit, AMapIsSizedFromThePixelsItsLightsReachSpansOnScreen) {
  using passes::ShadowMapPass;
  const glm::mat4 viewProj = glm::perspectiveRH_ZO(1.0f, 1.0f, 0.1f, 1000.0f) * glm::lookAt(glm::vec3(0), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
  const glm::vec3 eye(0.0f);
  auto need = [&](float distance, float radius) { return ShadowMapPass::neededSize(glm::vec4(0, 0, -distance, radius), 512, viewProj, eye, 500.0f); };
  // 2 tan(asin(1/d)) * 500 pixels across: 258 at d = 4, 126 at d = 8, 10 at d = 100.
  EXPECT_EQ(need(4.0f, 1.0f), 512u);
  EXPECT_EQ(need(8.0f, 1.0f), 128u);
  EXPECT_EQ(need(100.0f, 1.0f), ShadowMapPass::kMinSize);
  EXPECT_EQ(need(0.5f, 1.0f), 512u) << "the camera inside the reach";
  EXPECT_EQ(ShadowMapPass::neededSize(glm::vec4(0, 0, 10, 1), 512, viewProj, eye, 500.0f), ShadowMapPass::kMinSize) << "behind the camera";
  EXPECT_EQ(ShadowMapPass::neededSize(glm::vec4(0, 0, -1000, -1), 1024, viewProj, eye, 500.0f), 1024u) << "a directional light's map";
  EXPECT_EQ(ShadowMapPass::neededSize(glm::vec4(0, 0, -4, 1), 32, viewProj, eye, 500.0f), 32u) << "never above the allocated size";
}

TEST(ShadowMapFit, AFarCameraRendersSmallerMapsAndTheNearOneTheFullMapsAgain) {
  Scene scene = loadScene(test::defaultScenePath());
  RenderSettings settings = test::settingsFor(Policy::None, kW, kH);
  settings.reflectionProbes = false;
  // Full size: two layers (sun, spot) and two cubes of faces half as wide.
  const uint32_t side = settings.shadowMapSize, fullTexels = 2 * side * side + 12 * (side / 2) * (side / 2);
  RenderSettings fullSize = settings;
  fullSize.shadowMapsFitScreen = false;
  Renderer reference(scene, fullSize);
  const Camera near = defaultCamera(scene, reference.aspect());
  std::vector<FrameTiming> frames = test::renderStill(reference, near, 2);
  EXPECT_EQ(frames[0].shadowMapTexels, fullTexels);
  const FrameImages full = reference.readback();
  test::expectValidationClean(reference.validationMessages());

  // From five times as far, the point lights' and the spot's reach span few pixels.
  Camera far = near;
  far.position = near.target + 5.0f * (near.position - near.target);
  Renderer fitted(scene, settings);
  frames = test::renderStill(fitted, far, 2);
  EXPECT_EQ(frames[0].shadowMapViews, 2u + 12u);
  std::printf("from five times as far: %u of the %u full-size texels rendered\n", frames[0].shadowMapTexels, fullTexels);
  EXPECT_LT(frames[0].shadowMapTexels, fullTexels * 3 / 4);
  EXPECT_GE(frames[0].shadowMapTexels, side * side) << "the sun's map keeps its size";
  EXPECT_EQ(frames[1].shadowMapViews, 0u);
  const FrameImages farImage = fitted.readback();

  // Near again: the maps grow to what the near camera needs, and the frame equals that of a
  // renderer that only ever saw the near camera, within 2/255 (a map the near camera does not
  // see may keep twice the size that renderer gave it: the hysteresis).
  frames = test::renderStill(fitted, near, 2);
  EXPECT_GT(frames[0].shadowMapViews, 0u);
  EXPECT_EQ(frames[1].shadowMapViews, 0u);
  Renderer nearOnly(scene, settings);
  test::renderStill(nearOnly, near, 2);
  const FrameImages nearFitted = nearOnly.readback();
  EXPECT_LE(maxChannelDifference(fitted.readback(), nearFitted), 2) << "maps resized and rendered again equal maps fitted from the start";
  test::expectValidationClean(nearOnly.validationMessages());
  // Halfway out: each map would do with less, but not with a quarter: nothing is rendered.
  Camera between = near;
  between.position = near.target + 1.5f * (near.position - near.target);
  frames = test::renderStill(fitted, between, 1);
  EXPECT_EQ(frames[0].shadowMapViews, 0u) << "hysteresis: no map shrinks for a small step";
  test::expectValidationClean(fitted.validationMessages());

  // The fitted maps' shadows stay close to the full maps', near and far.
  Renderer farReference(scene, fullSize);
  test::renderStill(farReference, far, 2);
  const double nearShare = shareDifferingBeyond16(nearFitted, full), farShare = shareDifferingBeyond16(farImage, farReference.readback());
  std::printf("pixels differing by more than 16/255 from full-size maps: near %.4f, far %.4f\n", nearShare, farShare);
  EXPECT_LT(nearShare, 0.02);
  EXPECT_LT(farShare, 0.02);
}

}  // namespace
}  // namespace raybudget
