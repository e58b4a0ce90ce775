// Renders a scene with validation on and returns what the tests check.
#pragma once
#include <algorithm>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "raybudget/raybudget.h"
#include "raybudget/testing.h"
#include "vk/context.h"

namespace raybudget::test {

// The HDR frame's radiance at pixel (x, y).
inline glm::vec3 hdr(const FrameImages& img, uint32_t x, uint32_t y) {
  const size_t i = (size_t(y) * img.width + x) * 4;
  return {glm::unpackHalf1x16(img.hdrRgba16[i]), glm::unpackHalf1x16(img.hdrRgba16[i + 1]), glm::unpackHalf1x16(img.hdrRgba16[i + 2])};
}

// Comparisons of two frames' display (LDR) images over their colour channels, in 255ths: the
// largest difference, the pixels where a channel differs by more than `steps`, and the mean.
inline int largestLdrDifference(const FrameImages& a, const FrameImages& b) {
  int most = 0;
  for (size_t i = 0; i < a.ldrRgba8.size(); ++i)
    if (i % 4 != 3) most = std::max(most, std::abs(int(a.ldrRgba8[i]) - int(b.ldrRgba8[i])));
  return most;
}
inline size_t pixelsDifferingBy(const FrameImages& a, const FrameImages& b, int steps) {
  size_t n = 0;
  for (size_t i = 0; i + 3 < a.ldrRgba8.size(); i += 4) {
    int most = 0;
    for (size_t c = 0; c < 3; ++c) most = std::max(most, std::abs(int(a.ldrRgba8[i + c]) - int(b.ldrRgba8[i + c])));
    n += most > steps;
  }
  return n;
}
inline double meanLdrDifference(const FrameImages& a, const FrameImages& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.ldrRgba8.size(); ++i)
    if (i % 4 != 3) sum += std::abs(double(a.ldrRgba8[i]) - double(b.ldrRgba8[i]));
  return sum / double(std::max<size_t>(1, a.ldrRgba8.size() / 4 * 3));
}

// The CPU references checked every frame (raybudget/testing.h).
inline const testing::Checks kCheckSelection{true};

struct RenderResult {
  FrameImages images;
  std::vector<FrameTiming> timings;
  std::vector<std::string> validation;
  Camera camera;
};

// `frames` frames of `renderer` from one camera, and the timings of every frame, those still
// in flight included (Renderer::finish).
inline std::vector<FrameTiming> renderStill(Renderer& renderer, const Camera& camera, uint32_t frames) {
  std::vector<FrameTiming> t;
  for (uint32_t f = 0; f < frames; ++f)
    for (const FrameTiming& x : renderer.render(camera)) t.push_back(x);
  for (const FrameTiming& x : renderer.finish()) t.push_back(x);
  return t;
}

inline RenderResult renderWithValidation(const Scene& scene, uint32_t width, uint32_t height, uint32_t frames) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.validation = true;
  settings.shadowMapSize = 512;
  Renderer renderer(scene, settings);
  RenderResult r;
  r.camera = defaultCamera(scene, renderer.aspect());
  for (uint32_t f = 0; f < frames; ++f)
    for (const FrameTiming& t : renderer.render(r.camera)) r.timings.push_back(t);
  for (const FrameTiming& t : renderer.finish()) r.timings.push_back(t);
  r.images = renderer.readback();
  r.validation = renderer.validationMessages();
  return r;
}

// Settings with validation on, for `policy` at width x height.
inline RenderSettings settingsFor(Policy policy, uint32_t width, uint32_t height) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.validation = true;
  s.policy = policy;
  return s;
}

// One frame per camera: every frame's timings, the last frame's images and per-object
// metrics. A validation message fails the test.
struct RenderedFrames {
  FrameImages images;
  std::vector<ObjectMetrics> metrics;
  std::vector<FrameTiming> timings;
};
void expectValidationClean(const std::vector<std::string>& messages);
inline RenderedFrames renderFrames(const Scene& scene, const RenderSettings& s, const std::vector<Camera>& cameras,
                                   const testing::Checks& checks = {}) {
  RenderSettings settings = s;
  settings.objectMetrics = true;
  Renderer renderer(scene, settings, checks);
  RenderedFrames r;
  for (const Camera& c : cameras)
    for (const FrameTiming& t : renderer.render(c)) r.timings.push_back(t);
  for (const FrameTiming& t : renderer.finish()) r.timings.push_back(t);
  r.images = renderer.readback();
  r.metrics = renderer.objectMetrics();
  expectValidationClean(renderer.validationMessages());
  return r;
}

// The shadow classifier against full RT on one frame: `classified` with `s`, `all` and `none`
// alike (the policy replaced): its rays, full RT's, and the mean LDR difference from full RT
// of the classified image (`kept`) and of the shadow maps' (`fallback`).
struct ClassifierFrame {
  uint64_t rays, fullRays;
  double kept, fallback;
};
inline ClassifierFrame classifierAgainstFullRt(const Scene& scene, RenderSettings s, const Camera& camera) {
  s.policy = Policy::All;
  const RenderedFrames full = renderFrames(scene, s, {camera});
  s.policy = Policy::Classified;
  const RenderedFrames classified = renderFrames(scene, s, {camera});
  s.policy = Policy::None;
  const RenderedFrames raster = renderFrames(scene, s, {camera});
  EXPECT_EQ(full.timings.size(), 1u);
  EXPECT_EQ(classified.timings.size(), 1u);
  return {classified.timings.at(0).raysTraced, full.timings.at(0).raysTraced, meanLdrDifference(classified.images, full.images),
          meanLdrDifference(raster.images, full.images)};
}

// Making a renderer with `settings` is refused with a raybudget::Error that names `setting`.
inline void expectRefusedNaming(const Scene& scene, const RenderSettings& settings, const std::string& setting) {
  try {
    Renderer r(scene, settings);
    ADD_FAILURE() << "a bad " << setting << " was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(setting), std::string::npos) << e.what();
  }
}

// The same on a host's device.
inline void expectRefusedNamingWith(const Scene& scene, const RenderSettings& settings, const core::HostDevice& host, const std::string& what) {
  try {
    Renderer r(scene, settings, host);
    ADD_FAILURE() << "accepted, though " << what << " is wrong";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

// The objects each 8x8 tile of an object-ID image shows (tiles row by row; pixels showing
// no object left out).
inline std::vector<std::set<uint32_t>> objectsPerTile(const std::vector<uint32_t>& ids, uint32_t width, uint32_t height) {
  const uint32_t tilesX = (width + 7) / 8, tilesY = (height + 7) / 8;
  std::vector<std::set<uint32_t>> tiles(size_t(tilesX) * tilesY);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      if (const uint32_t id = ids[size_t(y) * width + x]; id != 0xFFFFFFFFu) tiles[size_t(y / 8) * tilesX + x / 8].insert(id);
  return tiles;
}

// A test on its own Vulkan context with validation on; any validation message fails it.
class ValidatedGpuTest : public ::testing::Test {
 protected:
  vk::Context ctx{vk::ContextOptions{true, ""}};
  void TearDown() override;
};

// Whether the device offers VK_KHR_ray_query (Tracer::Native); asked once.
inline bool nativeTracerAvailable() {
  static const bool available = vk::Context(vk::ContextOptions{false, ""}).rayQuerySupported();
  return available;
}

inline void expectValidationClean(const std::vector<std::string>& messages) {
  EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
}

inline void ValidatedGpuTest::TearDown() { expectValidationClean(ctx.validationMessages()); }

}  // namespace raybudget::test
