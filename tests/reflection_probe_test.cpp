// Reflection probes: the raster fallback reflects the scene captured from the probe's centre,
// parallax-corrected against its box, as the traced reflection does where the box's walls
// are what the mirror sees; a probe is captured once and again when an object inside its box
// moves; a probe whose centre lies inside a closed object gives way to the sky.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "shared/config.h"

#include "support/procedural.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

using test::hdr;

// A mirror facing +z at the origin, and behind the camera a green wall with a red patch off
// its centre (emitters, facing the mirror). The scene's bounds end at the wall, so the
// default probe's box has the wall as its far face.
struct MirrorAndWall {
  Scene scene;
  uint32_t mirror = 0, patch = 0;
  Camera camera;

  MirrorAndWall() {
    const glm::mat4 facingZ = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));  // +y to +z
    const glm::mat4 facingMinusZ = glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0));
    test::addObject(scene, test::quad(2.0f), facingZ, test::mirror());
    mirror = 0;
    test::addObject(scene, test::quad(6.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 8)) * facingMinusZ,
                    test::emitter(glm::vec3(0.0f, 2.0f, 0.0f)));
    test::addObject(scene, test::quad(0.8f), glm::translate(glm::mat4(1.0f), glm::vec3(1.2f, 0.6f, 7.9f)) * facingMinusZ,
                    test::emitter(glm::vec3(3.0f, 0.0f, 0.0f)));
    patch = 2;
    camera.position = {0.0f, 0.3f, 3.0f};
    camera.target = {0.0f, 0.0f, 0.0f};
  }
};

RenderSettings stillSettings(Policy policy) {
  RenderSettings s = test::settingsFor(policy, 64, 64);
  s.skyIntensity = 0.0f;  // a black sky: whatever the mirror shows comes from the scene
  return s;
}

FrameImages renderOnce(const Scene& scene, const RenderSettings& s, const Camera& camera, std::vector<FrameTiming>* timings = nullptr) {
  Renderer renderer(scene, s);
  const std::vector<FrameTiming> t = test::renderStill(renderer, camera, 1);
  if (timings) *timings = t;
  FrameImages img = renderer.readback();
  test::expectValidationClean(renderer.validationMessages());
  return img;
}

// The probe's parallax correction puts the wall, and the patch on it, where the traced
// reflection does: on the mirror's pixels the fallback's radiance is within 10% of the
// traced one on average, and the red patch covers the same pixels in both (90%).
TEST(ReflectionProbes, AMirrorFacingAWallShowsTheWallWhereTheTracedReflectionDoes) {
  const MirrorAndWall m;
  std::vector<FrameTiming> t;
  const FrameImages traced = renderOnce(m.scene, stillSettings(Policy::All), m.camera);
  const FrameImages raster = renderOnce(m.scene, stillSettings(Policy::None), m.camera, &t);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].probesCaptured, 1u);
  double tracedSum = 0.0, differenceSum = 0.0;
  size_t mirrorPixels = 0, redBoth = 0, redEither = 0;
  for (uint32_t y = 0; y < traced.height; ++y)
    for (uint32_t x = 0; x < traced.width; ++x) {
      if (raster.objectIds[size_t(y) * raster.width + x] != m.mirror) continue;
      ++mirrorPixels;
      const glm::vec3 a = hdr(traced, x, y), b = hdr(raster, x, y);
      tracedSum += a.r + a.g + a.b;
      differenceSum += std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
      const bool redA = a.r > a.g, redB = b.r > b.g;
      redBoth += redA && redB;
      redEither += redA || redB;
    }
  ASSERT_GT(mirrorPixels, 1000u) << "the mirror fills much of the frame";
  ASSERT_GT(redBoth, 20u) << "the patch is reflected";
  EXPECT_LT(differenceSum / tracedSum, 0.10);
  EXPECT_GT(double(redBoth) / double(redEither), 0.9);
  // Without probes the mirror shows the black sky.
  RenderSettings off = stillSettings(Policy::None);
  off.reflectionProbes = false;
  const FrameImages sky = renderOnce(m.scene, off, m.camera);
  const glm::vec3 centre = hdr(sky, 32, 32);
  EXPECT_LT(centre.r + centre.g + centre.b, 0.01f);
}

// Captured on the first frame, skipped while nothing moves, captured again when an object
// inside the box moves, one face per frame and then one prefiltered level per frame (the old
// probe shown meanwhile): when the last level is in, the frame equals a fresh renderer's.
TEST(ReflectionProbes, AreCapturedOnceAndAgainWhenAnObjectInsideTheirBoxMoves) {
  MirrorAndWall m;
  Renderer renderer(m.scene, stillSettings(Policy::None));
  const std::vector<FrameTiming> still = test::renderStill(renderer, m.camera, 3);
  ASSERT_EQ(still.size(), 3u);
  EXPECT_EQ(still[0].probesCaptured, 1u);
  for (size_t i = 1; i < still.size(); ++i) {
    EXPECT_EQ(still[i].probesCaptured, 0u);
    EXPECT_EQ(still[i].skipped[size_t(Pass::ReflectionProbes)], PassSkip::ProbesCurrent);
  }
  const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(-2.4f, 0.0f, 0.0f)) * m.scene.objects[m.patch].transform;
  renderer.setObjectTransform(m.patch, moved);
  setObjectTransform(m.scene, m.patch, moved);
  std::vector<FrameTiming> after = test::renderStill(renderer, m.camera, 1);
  const FrameImages during = renderer.readback();
  for (const FrameTiming& t : test::renderStill(renderer, m.camera, 6 + RB_ENV_MIPS - 1)) after.push_back(t);
  ASSERT_EQ(after.size(), size_t(6 + RB_ENV_MIPS));
  for (size_t i = 0; i + 1 < after.size(); ++i) {
    EXPECT_EQ(after[i].probesCaptured, 0u) << "frame " << i << " captures a face or prefilters a level";
    EXPECT_EQ(after[i].skipped[size_t(Pass::ReflectionProbes)], PassSkip::None);
  }
  EXPECT_EQ(after.back().probesCaptured, 1u) << "the last level completes the probe";
  EXPECT_EQ(test::renderStill(renderer, m.camera, 1)[0].skipped[size_t(Pass::ReflectionProbes)], PassSkip::ProbesCurrent);
  const FrameImages updated = renderer.readback();
  const FrameImages fresh = renderOnce(m.scene, stillSettings(Policy::None), m.camera);
  float worst = 0.0f;
  for (uint32_t y = 0; y < fresh.height; ++y)
    for (uint32_t x = 0; x < fresh.width; ++x) {
      const glm::vec3 d = glm::abs(hdr(updated, x, y) - hdr(fresh, x, y));
      worst = std::max(worst, std::max(d.r, std::max(d.g, d.b)));
    }
  EXPECT_LT(worst, 1e-3f) << "the moved patch is reflected where it is now";
  // While the probe was captured again the mirror showed the old one (the patch where it was),
  // over the same G-buffer.
  float changed = 0.0f;
  for (uint32_t y = 0; y < fresh.height; ++y)
    for (uint32_t x = 0; x < fresh.width; ++x) changed = std::max(changed, glm::length(hdr(during, x, y) - hdr(updated, x, y)));
  EXPECT_GT(changed, 0.05f) << "the completed recapture changes the reflection";
  test::expectValidationClean(renderer.validationMessages());
}

// A probe placed inside a closed box sees the box's inner faces (the back of one-sided
// surfaces), so the fallback keeps the sky: the frame equals one rendered without probes. So
// does one placed against the floor, which would show the floor in most directions. Without
// an authored probe none is placed there at all (the default one's centre is inside the
// box's bounds).
TEST(ReflectionProbes, AProbeInsideAClosedObjectGivesWayToTheSky) {
  Scene scene;
  test::addObject(scene, test::quad(3.0f), glm::mat4(1.0f), test::mirror(0.1f));
  Material stone;
  stone.metallic = 0.0f;
  stone.baseColorFactor = glm::vec4(0.8f, 0.3f, 0.2f, 1.0f);
  test::addObject(scene, test::subdividedCube(1), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, 0.0f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)), stone);
  Camera cam;
  cam.position = {0.0f, 4.0f, 4.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  RenderSettings on = test::settingsFor(Policy::None, 64, 64), off = on;
  off.reflectionProbes = false;
  std::vector<FrameTiming> t;
  EXPECT_TRUE(reflectionProbesOf(scene).empty());
  renderOnce(scene, on, cam, &t);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].skipped[size_t(Pass::ReflectionProbes)], PassSkip::NoReflectionProbe);
  scene.reflectionProbes = {{"inside", glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(-3.0f, -0.1f, -3.0f), glm::vec3(3.0f, 1.1f, 3.0f)}};
  const FrameImages withProbe = renderOnce(scene, on, cam, &t);
  const FrameImages sky = renderOnce(scene, off, cam);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].probesCaptured, 1u);
  EXPECT_TRUE(withProbe.hdrRgba16 == sky.hdrRgba16) << "the probe from inside the box was used";
  scene.reflectionProbes[0].center = glm::vec3(2.0f, 0.05f, 2.0f);  // 0.05 above the floor, the diagonal 8.5
  const FrameImages against = renderOnce(scene, on, cam, &t);
  EXPECT_EQ(t[0].probesCaptured, 1u);
  EXPECT_TRUE(against.hdrRgba16 == sky.hdrRgba16) << "the probe against the floor was used";
  scene.reflectionProbes[0].center = glm::vec3(2.0f, 0.8f, 2.0f);  // in the clear: used
  EXPECT_FALSE(renderOnce(scene, on, cam).hdrRgba16 == sky.hdrRgba16);
}

}  // namespace
}  // namespace raybudget
