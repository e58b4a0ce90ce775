// The effects pass's temporal fill (RayTracingSettings::temporalFill,
// shaders/include/fill_history.glsl): a pixel a reduced rate skips keeps what it was when last
// traced while its object, its distance and the view direction still match. Under a still
// camera a quarter rate then shows the full-rate image once every pixel of each quad has been
// traced; where the view turns or another object takes the pixel, nothing is carried and the
// frame is the spatial fill's alone.
#include <algorithm>
#include <cstdlib>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "support/procedural.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

RenderSettings effectsOnly(ItemRate rate, bool temporal, uint32_t w, uint32_t h) {
  RenderSettings s = test::settingsFor(Policy::All, w, h);
  s.rayTracing.rate = rate;
  s.rayTracing.shadows = false;  // the shadow pass fills spatially alone
  s.rayTracing.temporalFill = temporal;
  s.screenSpaceReflections = false;  // it reads the previous frame's image, which differs with and without
  return s;
}

// Renders `cameras` in turn; `between(renderer, frame)` runs before each frame.
FrameImages lastFrame(const Scene& scene, const RenderSettings& s, const std::vector<Camera>& cameras,
                      const std::function<void(Renderer&, size_t)>& between = {}) {
  Renderer r(scene, s);
  for (size_t f = 0; f < cameras.size(); ++f) {
    if (between) between(r, f);
    r.render(cameras[f]);
  }
  r.finish();
  const FrameImages images = r.readback();
  test::expectValidationClean(r.validationMessages());
  return images;
}

// The court's mirrors, chrome and glass at a quarter and a sixteenth rate under a still camera:
// after the frames that trace each pixel of a quad (a 4x4 block) once, the frame equals full
// rate's but for the half floats the history keeps (one step of 255; at 384x216 a single pixel differs by 3,
// at either rate); without the history it does not. At 1/16 a value is carried 15 frames: a still view must read as no turn at all.
TEST(TemporalFill, AStillCameraAtAReducedRateShowsTheFullRateImage) {
  constexpr uint32_t kW = 384, kH = 216;
  const Scene scene = loadScene(test::defaultScenePath());
  const Camera cam = defaultCamera(scene, float(kW) / float(kH));
  for (const auto& [rate, frames] : {std::pair{ItemRate::Quarter, 6}, std::pair{ItemRate::Sixteenth, 18}}) {
    const std::vector<Camera> still(size_t(frames), cam);
    const FrameImages full = lastFrame(scene, effectsOnly(ItemRate::Full, false, kW, kH), still);
    const FrameImages temporal = lastFrame(scene, effectsOnly(rate, true, kW, kH), still);
    const FrameImages spatial = lastFrame(scene, effectsOnly(rate, false, kW, kH), still);
    EXPECT_LE(test::largestLdrDifference(full, temporal), 4) << itemRateName(rate);
    EXPECT_LE(test::pixelsDifferingBy(full, temporal, 1), 2u) << itemRateName(rate) << ": one step of 255 at all but a pixel or two";
    EXPECT_GT(test::largestLdrDifference(full, spatial), 16) << itemRateName(rate) << ": the spatial fill alone differs where reflections hold detail";
  }
}

// A camera that turns 20 degrees about the target between two frames: the view direction at
// every point turned past the history's limit, so the frame equals the one without history.
TEST(TemporalFill, NothingIsCarriedWhereTheViewTurned) {
  const Scene scene = loadScene(test::defaultScenePath());
  Camera start = defaultCamera(scene, 192.0f / 112.0f);
  start.target = glm::vec3(0.0f, 1.0f, 0.0f);  // the court's centre: the camera circles it
  Camera turned = start;
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(20.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  turned.position = start.target + glm::vec3(turn * glm::vec4(start.position - start.target, 0.0f));
  std::vector<Camera> frames(5, start);
  frames.push_back(turned);
  const FrameImages temporal = lastFrame(scene, effectsOnly(ItemRate::Quarter, true, 192, 112), frames);
  const FrameImages spatial = lastFrame(scene, effectsOnly(ItemRate::Quarter, false, 192, 112), frames);
  EXPECT_EQ(test::largestLdrDifference(temporal, spatial), 0);
}

// Two coplanar mirrors, one reflecting red and one green, trade places under a still camera:
// every pixel's surface lies where it did, at the same distance, on another object, so no
// history may be taken and the frame equals the one without history.
TEST(TemporalFill, HistoryNeverCrossesObjects) {
  const Scene scene = test::twoMirrors();
  Camera cam;
  cam.position = {0.0f, 4.0f, 4.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  const std::vector<Camera> frames(6, cam);
  auto swapAtFrame5 = [](Renderer& r, size_t f) {
    if (f != 5) return;
    r.setObjectTransform(0, glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f)));
    r.setObjectTransform(1, glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.0f, 0.0f)));
  };
  auto settings = [](bool temporal) {
    RenderSettings s = effectsOnly(ItemRate::Quarter, temporal, 128, 96);
    s.skyIntensity = 0.0f;
    return s;
  };
  const FrameImages temporal = lastFrame(scene, settings(true), frames, swapAtFrame5);
  const FrameImages spatial = lastFrame(scene, settings(false), frames, swapAtFrame5);
  EXPECT_EQ(test::largestLdrDifference(temporal, spatial), 0);
  // And without the swap the history is taken: the frames differ.
  EXPECT_GT(test::largestLdrDifference(lastFrame(scene, settings(true), frames), lastFrame(scene, settings(false), frames)), 0);
}

RenderSettings shadowsOnly(ItemRate rate, bool temporal, uint32_t w, uint32_t h, uint32_t shadowMapSize = 1024) {
  RenderSettings s = test::settingsFor(Policy::All, w, h);
  s.rayTracing.rate = rate;
  s.rayTracing.reflections = false;
  s.rayTracing.refractions = false;
  s.rayTracing.temporalFill = temporal;
  s.screenSpaceReflections = false;
  s.shadowMapSize = shadowMapSize;
  return s;
}

// Shadows alone (include/shadow_history.glsl): under a still camera a quarter rate shows the
// full-rate shadows once each pixel of a quad has been traced, but for the history's 8-bit
// steps of the maps' error; the spatial fill alone does not.
TEST(TemporalFill, ShadowsUnderAStillCameraAtAQuarterRateShowTheFullRateImage) {
  const Scene scene = loadScene(test::defaultScenePath());
  const std::vector<Camera> frames(6, defaultCamera(scene, 192.0f / 112.0f));
  const FrameImages full = lastFrame(scene, shadowsOnly(ItemRate::Full, false, 192, 112), frames);
  const FrameImages temporal = lastFrame(scene, shadowsOnly(ItemRate::Quarter, true, 192, 112), frames);
  const FrameImages spatial = lastFrame(scene, shadowsOnly(ItemRate::Quarter, false, 192, 112), frames);
  std::printf("still camera, shadows at 1/4: largest difference from full rate %d with the history, %d without\n",
              test::largestLdrDifference(full, temporal), test::largestLdrDifference(full, spatial));
  EXPECT_LE(test::largestLdrDifference(full, temporal), 3);
  EXPECT_GT(test::largestLdrDifference(full, spatial), 16) << "the spatial fill alone misses thin shadows' detail";
}

// A shadow does not move with the view: under an orbit of a degree a frame the history is
// carried wherever the point traced still shows within half a pixel, so the frame lies closer
// to full rate than the spatial fill's alone. With coarse (128-texel) shadow maps, whose error
// the rays correct over wide areas (with the default maps the two fills' frames lie within 2%
// of each other: what is left is mostly at silhouettes the camera uncovers).
TEST(TemporalFill, ShadowsFollowAMovingCamera) {
  const Scene scene = loadScene(test::defaultScenePath());
  Camera start = defaultCamera(scene, 192.0f / 112.0f);
  start.target = glm::vec3(0.0f, 1.0f, 0.0f);
  std::vector<Camera> frames;
  for (int f = 0; f < 8; ++f) {
    Camera c = start;
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(float(f)), glm::vec3(0.0f, 1.0f, 0.0f));
    c.position = start.target + glm::vec3(turn * glm::vec4(start.position - start.target, 0.0f));
    frames.push_back(c);
  }
  const FrameImages full = lastFrame(scene, shadowsOnly(ItemRate::Full, false, 192, 112, 128), frames);
  const double temporal = test::meanLdrDifference(full, lastFrame(scene, shadowsOnly(ItemRate::Quarter, true, 192, 112, 128), frames));
  const double spatial = test::meanLdrDifference(full, lastFrame(scene, shadowsOnly(ItemRate::Quarter, false, 192, 112, 128), frames));
  std::printf("orbit, shadows at 1/4: mean difference from full rate %.4f with the history, %.4f without\n", temporal, spatial);
  EXPECT_LT(temporal, 0.92 * spatial) << "measured 0.86 against 1.01";
}

}  // namespace
}  // namespace raybudget
