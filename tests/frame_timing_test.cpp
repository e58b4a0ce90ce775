// Per-pass timestamps: every executed pass reports a time, the static environment only on
// the first frame, and results arrive for every frame without the caller waiting on each.
#include <gtest/gtest.h>

#include "support/gltf_fixture.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

Scene twoTriangles() {
  const auto dir = test::freshTempDir("timing");
  return loadScene(test::GltfFixture::triangles({{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {0, 0.5f, 0}, {0.3f, 1, 0}, {-0.3f, 1, 0}},
                                                {0, 1, 2, 0, 2, 3, 4, 5, 6})
                       .write(dir, "scene"));
}

TEST(FrameTiming, EveryPassIsTimedAndTheEnvironmentOnlyOnce) {
  const test::RenderResult r = test::renderWithValidation(twoTriangles(), 128, 96, 5);
  test::expectValidationClean(r.validation);
  ASSERT_EQ(r.timings.size(), 5u);
  for (size_t i = 0; i < r.timings.size(); ++i) {
    const FrameTiming& t = r.timings[i];
    EXPECT_EQ(t.frame, i) << "timings arrive in frame order";
    for (Pass p : {Pass::GBuffer, Pass::ShadowMaps, Pass::Lighting, Pass::EnvFallback, Pass::Compose}) {
      ASSERT_TRUE(t.passMs[size_t(p)].has_value()) << passName(p) << " frame " << i;
      EXPECT_GE(*t.passMs[size_t(p)], 0.0);
    }
    EXPECT_EQ(t.passMs[size_t(Pass::Environment)].has_value(), i == 0) << "the static environment is built once";
  }
}

TEST(FrameTiming, RenderReturnsEarlierFramesWithoutWaitingForTheCurrentOne) {
  RenderSettings settings;
  settings.width = 64;
  settings.height = 64;
  settings.validation = true;
  Renderer renderer(twoTriangles(), settings);
  const Scene scene = twoTriangles();
  const Camera cam = defaultCamera(scene, 1.0f);
  EXPECT_TRUE(renderer.render(cam).empty()) << "frame 0 is still in flight";
  EXPECT_TRUE(renderer.render(cam).empty()) << "two frames in flight";
  const auto third = renderer.render(cam);
  ASSERT_EQ(third.size(), 1u);
  EXPECT_EQ(third[0].frame, 0u);
  const auto rest = renderer.finish();
  ASSERT_EQ(rest.size(), 2u);
  EXPECT_EQ(rest[0].frame, 1u);
  EXPECT_EQ(rest[1].frame, 2u);
  test::expectValidationClean(renderer.validationMessages());
}

TEST(FrameTiming, BadSettingsAreRejected) {
  RenderSettings s;
  s.width = 0;
  EXPECT_THROW(Renderer(twoTriangles(), s), Error);
  s = RenderSettings{};
  s.exposure = std::nanf("");
  EXPECT_THROW(Renderer(twoTriangles(), s), Error);
}

}  // namespace
}  // namespace raybudget
