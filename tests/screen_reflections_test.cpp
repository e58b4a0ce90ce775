// Screen-space reflections: a mirror floor in front of a wall reflects the wall, which is on
// screen, as the traced reflection does, from the second frame on (the first has no earlier
// image); switched off, the floor shows the (black) sky there.
#include <algorithm>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "support/procedural.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

using test::hdr;

// A mirror floor, and on it a green wall with a red stripe facing the camera (emitters). The
// floor's normal map holds `normalMap` (none where it is +z).
Scene floorAndWall(glm::vec3 normalMap = {0, 0, 1}) {
  Scene scene;
  Material floor = test::mirror();
  if (normalMap != glm::vec3(0, 0, 1)) floor.normalTexture = test::addFlatNormalMap(scene, normalMap);
  test::addObject(scene, test::texturedQuad(4.0f), glm::mat4(1.0f), floor);
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

// On the floor's pixels where the traced reflection shows the wall: how far the screen-space
// reflection (and the fallback without it) is from it, summed over the channels relative to
// the traced sum, and how many show the stripe in both against either.
struct FloorAgreement {
  size_t pixels = 0, redBoth = 0, redEither = 0;
  double ssrError = 0.0, offError = 0.0;
};

FloorAgreement floorAgreement(const Rendered& traced, const Rendered& ssr, const Rendered& off) {
  FloorAgreement r;
  double tracedSum = 0.0;
  const FrameImages& t = traced.image;
  for (uint32_t y = 0; y < t.height; ++y)
    for (uint32_t x = 0; x < t.width; ++x) {
      const glm::vec3 a = hdr(t, x, y), b = hdr(ssr.image, x, y), c = hdr(off.image, x, y);
      if (t.objectIds[size_t(y) * t.width + x] != 0u || a.r + a.g < 0.5f) continue;  // the floor where it reflects the wall
      ++r.pixels;
      tracedSum += a.r + a.g + a.b;
      r.ssrError += std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
      r.offError += std::abs(a.r - c.r) + std::abs(a.g - c.g) + std::abs(a.b - c.b);
      r.redBoth += a.r > a.g && b.r > b.g;
      r.redEither += a.r > a.g || b.r > b.g;
    }
  r.ssrError /= std::max(tracedSum, 1e-9);
  r.offError /= std::max(tracedSum, 1e-9);
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
  const FloorAgreement a = floorAgreement(traced, ssr, off);
  ASSERT_GT(a.pixels, 300u) << "the floor reflects the wall over much of the frame";
  ASSERT_GT(a.redBoth, 10u) << "the stripe is reflected";
  EXPECT_LT(a.ssrError, 0.15);
  EXPECT_GT(a.offError, 0.9) << "without them the floor shows the black sky";
  EXPECT_GT(double(a.redBoth) / double(a.redEither), 0.9);
}

// A normal map leaning the floor's normal 53 degrees sideways sends the mirror ray below the
// floor over the middle of the frame; the tracer turns such a ray back above the floor
// (about its plane), and the screen-space reflection must follow the same ray: marched as it
// stood, it met the floor itself and showed the sky (error 0.58 against 0.28 following it).
TEST(ScreenSpaceReflections, ANormalMappedMirrorReflectsAlongTheRayTheTracerTurnsAboveTheFloor) {
  const Scene scene = floorAndWall(glm::vec3(0.8f, 0.0f, 0.6f));
  const Rendered traced = render(scene, Policy::All, false, 1);
  const Rendered ssr = render(scene, Policy::None, true, 2);
  const Rendered off = render(scene, Policy::None, false, 2);
  const FloorAgreement a = floorAgreement(traced, ssr, off);
  ASSERT_GT(a.pixels, 300u) << "the tilted floor still reflects the wall over much of the frame";
  std::printf("normal-mapped floor: %zu pixels reflect the wall, screen-space error %.3f, without it %.3f\n", a.pixels, a.ssrError,
              a.offError);
  EXPECT_LT(a.ssrError, 0.4);
  EXPECT_GT(a.offError, 0.9) << "without them the floor shows the black sky";
}

}  // namespace
}  // namespace raybudget
