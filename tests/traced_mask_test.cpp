// The traced mask (core::FrameOutputs::tracedMask) against a CPU oracle from the G-buffer:
// under `all` a pixel is marked for reflections exactly where its roughness is within the
// cut-off, for refractions where it transmits, for shadows (the default sun alone) where its
// normal faces the sun; `none` marks nothing, also right after a traced frame; a budgeted
// policy marks only pixels of objects whose item it selected.
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

float half(uint16_t h) { return glm::unpackHalf1x16(h); }

struct MaskCounts {
  size_t reflections = 0, refractions = 0, shadows = 0, mismatches = 0, marked = 0;
};

// Under `all`, at full rate: what the trace passes must have marked.
MaskCounts compareWithOracle(const FrameImages& img, const RenderSettings& s, glm::vec3 sunTravel) {
  MaskCounts c;
  for (size_t i = 0; i < img.objectIds.size(); ++i) {
    const uint32_t mask = img.tracedMask[i];
    if (mask) ++c.marked;
    const bool surface = img.objectIds[i] != 0xFFFFFFFFu && half(img.roughTransIor[i * 4 + 3]) <= 0.5f;
    const float roughness = half(img.roughTransIor[i * 4]), transmission = half(img.roughTransIor[i * 4 + 1]);
    const float metallic = float(img.baseMetal[i * 4 + 3]) / 255.0f;
    const glm::vec3 n = glm::normalize(glm::vec3(half(img.normals[i * 4]), half(img.normals[i * 4 + 1]), half(img.normals[i * 4 + 2])));
    const float facing = surface ? glm::dot(n, -sunTravel) : 0.0f;
    const bool reflects = surface && roughness <= s.rayTracing.maxRoughness;
    const bool refracts = surface && transmission * (1.0f - metallic) > 0.0f;
    c.reflections += reflects;
    c.refractions += refracts;
    c.shadows += facing > 0.0f;
    if (bool(mask & core::kTracedReflections) != reflects || bool(mask & core::kTracedRefractions) != refracts) ++c.mismatches;
    // Facing by a hair either way: the shader's dot product may round differently.
    if (std::fabs(facing) > 1e-5f && bool(mask & core::kTracedShadows) != (facing > 0.0f)) ++c.mismatches;
  }
  return c;
}

TEST(TracedMask, FullRayTracingMarksExactlyThePixelsTheOracleSays) {
  Scene scene = loadScene(test::defaultScenePath());
  scene.lights = {defaultSun()};  // one directional light: "lit" is "faces the sun"
  RenderSettings s = test::settingsFor(Policy::All, 160, 96);
  Renderer renderer(scene, s);
  const Camera camera = defaultCamera(scene, renderer.aspect());
  renderer.render(camera);
  renderer.finish();
  const FrameImages img = renderer.readback(true);
  test::expectValidationClean(renderer.validationMessages());
  const MaskCounts c = compareWithOracle(img, s, defaultSun().direction);
  EXPECT_EQ(c.mismatches, 0u);
  // The view holds mirrors, glass and sunlit surfaces: the oracle is not vacuous.
  EXPECT_GT(c.reflections, 200u);
  EXPECT_GT(c.refractions, 50u);
  EXPECT_GT(c.shadows, 2000u);
}

TEST(TracedMask, NothingIsMarkedWithoutTracingEvenAfterATracedFrame) {
  const Scene scene = loadScene(test::defaultScenePath());
  Renderer renderer(scene, test::settingsFor(Policy::All, 96, 64));
  const Camera camera = defaultCamera(scene, renderer.aspect());
  renderer.render(camera);
  renderer.finish();
  const FrameImages traced = renderer.readback(true);
  EXPECT_GT(std::count_if(traced.tracedMask.begin(), traced.tracedMask.end(), [](uint32_t m) { return m != 0; }), 500);
  renderer.restartSelection(Policy::None, 4.0f);
  renderer.render(camera);
  renderer.finish();
  const FrameImages none = renderer.readback(true);
  EXPECT_EQ(std::count_if(none.tracedMask.begin(), none.tracedMask.end(), [](uint32_t m) { return m != 0; }), 0);
  test::expectValidationClean(renderer.validationMessages());
}

TEST(TracedMask, ABudgetedPolicyMarksOnlyTheItemsItSelected) {
  const Scene scene = loadScene(test::defaultScenePath());
  for (Policy policy : {Policy::Density, Policy::Benefit}) {
    RenderSettings s = test::settingsFor(policy, 128, 80);
    s.budgetMs = 30.0f;
    s.learnTimeScale = false;  // the prior: the same selection on any machine
    s.objectMetrics = true;
    Renderer renderer(scene, s);
    const Camera camera = defaultCamera(scene, renderer.aspect());
    for (int f = 0; f < 3; ++f) renderer.render(camera);
    renderer.finish();
    const FrameImages img = renderer.readback(true);
    const std::vector<ObjectMetrics> metrics = renderer.objectMetrics();
    size_t marked = 0, outside = 0;
    uint32_t selectedItems = 0;
    for (const ObjectMetrics& m : metrics) selectedItems |= m.selectedItems;
    for (size_t i = 0; i < img.tracedMask.size(); ++i) {
      const uint32_t mask = img.tracedMask[i];
      if (!mask) continue;
      ++marked;
      const uint32_t id = img.objectIds[i];
      // Items are the RB_RT_* bits in the same order: shadows 1, reflections 2, refractions 4.
      if (id >= metrics.size() || (mask & ~metrics[id].selectedItems) != 0u) ++outside;
    }
    EXPECT_GT(marked, 0u) << policyName(policy);
    EXPECT_EQ(outside, 0u) << policyName(policy);
    EXPECT_NE(selectedItems, 0u);
    test::expectValidationClean(renderer.validationMessages());
  }
}

}  // namespace
}  // namespace raybudget
