// Screen-space reflections: a mirror floor in front of a wall reflects the wall, which is on
// screen, as the traced reflection does, from the second frame on (the first has no earlier
// image); switched off, the floor shows the (black) sky there.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "support/procedural.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

using test::hdr;

// A mirror floor, and on it a green wall with a red stripe facing the camera (emitters).
Scene floorAndWall() {
  Scene scene;
  test::addObject(scene, test::quad(4.0f), glm::mat4(1.0f), test::mirror());
  const glm::mat4 facingZ = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));
  test::addObject(scene, test::quad(2.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 2.0f, -3.0f)) * facingZ,
                  test::emitter(glm::vec3(0.0f, 2.0f, 0.0f)));
  test::addObject(scene, test::quad(0.5f), glm::translate(glm::mat4(1.0f), glm::vec3(0.8f, 1.0f, -2.95f)) * facingZ,
                  test::emitter(glm::vec3(3.0f, 0.0f, 0.0f)));
  return scene;
}

struct Rendered {
  FrameImages image;
  std::vector<FrameTiming> timings;
};

Rendered render(const Scene& scene, Policy policy, bool ssr, uint32_t frames) {
  RenderSettings s = test::settingsFor(policy, 96, 64);
  s.skyIntensity = 0.0f;
  s.reflectionProbes = false;  // the sky, black, wherever the screen holds nothing to reflect
  s.screenSpaceReflections = ssr;
  Camera cam;
  cam.position = {0.0f, 1.2f, 4.0f};
  cam.target = {0.0f, 0.6f, -3.0f};
  Renderer renderer(scene, s);
  Rendered r{{}, test::renderStill(renderer, cam, frames)};
  r.image = renderer.readback();
  test::expectValidationClean(renderer.validationMessages());
  return r;
}

// On the floor's pixels that reflect the wall, the screen-space reflection is within 15% of
// the traced one on average, the stripe where the traced one has it (90%).
TEST(ScreenSpaceReflections, AMirrorFloorReflectsTheWallOnScreenAsTheTracedReflectionDoes) {
  const Scene scene = floorAndWall();
  const Rendered traced = render(scene, Policy::All, false, 1);
  const Rendered ssr = render(scene, Policy::None, true, 2);
  const Rendered off = render(scene, Policy::None, false, 2);
  ASSERT_EQ(ssr.timings.size(), 2u);
  EXPECT_EQ(ssr.timings[0].skipped[size_t(Pass::ScreenSpaceReflections)], PassSkip::NoPreviousFrame);
  EXPECT_TRUE(ssr.timings[1].passMs[size_t(Pass::ScreenSpaceReflections)].has_value());
  EXPECT_EQ(off.timings[1].skipped[size_t(Pass::ScreenSpaceReflections)], PassSkip::FallbackOff);
  double tracedSum = 0.0, ssrError = 0.0, offError = 0.0;
  size_t pixels = 0, redBoth = 0, redEither = 0;
  const FrameImages& t = traced.image;
  for (uint32_t y = 0; y < t.height; ++y)
    for (uint32_t x = 0; x < t.width; ++x) {
      const glm::vec3 a = hdr(t, x, y), b = hdr(ssr.image, x, y), c = hdr(off.image, x, y);
      if (t.objectIds[size_t(y) * t.width + x] != 0u || a.r + a.g < 0.5f) continue;  // the floor where it reflects the wall
      ++pixels;
      tracedSum += a.r + a.g + a.b;
      ssrError += std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
      offError += std::abs(a.r - c.r) + std::abs(a.g - c.g) + std::abs(a.b - c.b);
      redBoth += a.r > a.g && b.r > b.g;
      redEither += a.r > a.g || b.r > b.g;
    }
  ASSERT_GT(pixels, 300u) << "the floor reflects the wall over much of the frame";
  ASSERT_GT(redBoth, 10u) << "the stripe is reflected";
  EXPECT_LT(ssrError / tracedSum, 0.15);
  EXPECT_GT(offError / tracedSum, 0.9) << "without them the floor shows the black sky";
  EXPECT_GT(double(redBoth) / double(redEither), 0.9);
}

}  // namespace
}  // namespace raybudget
