// The heuristic's per-object pass on the GPU against its CPU reference: coverage counted
// from the same object-ID image, the classifier's reflection and refraction pixels from the
// same G-buffer materials, and A, P, D, V, C, R from engine/src/select/metrics.h.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "select/metrics.h"
#include "select/object_params.h"
#include "shared/selection.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

void expectNear(float gpu, float cpu, float rel, float abs, const std::string& what) {
  EXPECT_LE(std::fabs(gpu - cpu), rel * std::fabs(cpu) + abs + 1e-30f) << what << ": GPU " << gpu << ", CPU " << cpu;
}

// Vulkan lets a float division be off by 2.5 ULP (lavapipe divides exactly, NVIDIA does
// not): the centroid behind P takes two divisions and lies in [-1, 1], so P may differ from
// the CPU's by about 8e-7 however small P is. V, C and R inherit that through A·P/D.
constexpr float kCentroidSlack = 1e-6f;

// The classifier's CPU reference, from the G-buffer's materials as the trace shader reads
// them: 1 a reflection pixel, 2 a refraction pixel (both possible), 0 unlit or neither.
uint32_t pixelClasses(const FrameImages& img, size_t pixel, float maxRoughness) {
  const float roughness = glm::unpackHalf1x16(img.roughTransIor[4 * pixel]), transmission = glm::unpackHalf1x16(img.roughTransIor[4 * pixel + 1]);
  const float unlit = glm::unpackHalf1x16(img.roughTransIor[4 * pixel + 3]), metallic = float(img.baseMetal[4 * pixel + 3]) / 255.0f;
  if (unlit > 0.5f) return 0;
  return (roughness <= maxRoughness ? 1u : 0u) | (transmission * (1.0f - metallic) > 0.0f ? 2u : 0u);
}

// Pixels the classifier marked over a scene (the checks below need some of each).
struct Classified {
  uint32_t reflection = 0, refraction = 0, detailed = 0;
};

glm::vec3 shadingNormal(const FrameImages& img, size_t pixel) {
  const uint16_t* n = &img.normals[4 * pixel];
  return glm::normalize(glm::vec3(glm::unpackHalf1x16(n[0]), glm::unpackHalf1x16(n[1]), glm::unpackHalf1x16(n[2])));
}

// The detail count's CPU reference (shared/selection.h's RB_FILL_DETAIL_COS): per object, the
// pixels needing reflection or refraction rays in a 2x2 quad (at even coordinates, as the
// coverage pass gathers them) with a pixel of the object whose normal is further from theirs
// than the cosine; `ambiguous` counts those whose decision a normal within 1e-5 of the cosine
// makes (the GPU normalises and takes the dot product in its own roundings).
void detailedPixels(const FrameImages& img, uint32_t w, uint32_t h, float maxRoughness, std::vector<uint32_t>& detailed,
                    std::vector<uint32_t>& ambiguous) {
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t pixel = size_t(y) * w + x;
      const uint32_t id = img.objectIds[pixel];
      if (id == 0xFFFFFFFFu || pixelClasses(img, pixel, maxRoughness) == 0) continue;
      bool apart = false, near = false;
      for (uint32_t qy = y & ~1u; qy < std::min(h, (y & ~1u) + 2); ++qy)
        for (uint32_t qx = x & ~1u; qx < std::min(w, (x & ~1u) + 2); ++qx) {
          const size_t other = size_t(qy) * w + qx;
          if (other == pixel || img.objectIds[other] != id) continue;
          const float d = glm::dot(shadingNormal(img, pixel), shadingNormal(img, other));
          apart = apart || d < float(RB_FILL_DETAIL_COS);
          near = near || std::fabs(d - float(RB_FILL_DETAIL_COS)) < 1e-5f;
        }
      detailed[id] += apart;
      ambiguous[id] += near;
    }
}

// Returns how many 8x8 tiles show more than three objects (the coverage pass sums three
// per tile in registers and adds the pixels of any further one on its own).
size_t checkScene(const Scene& scene, const Camera& camera, uint32_t w, uint32_t h, Classified* classified = nullptr) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  s.validation = true;
  s.objectMetrics = true;
  Renderer renderer(scene, s);
  renderer.render(camera);
  renderer.finish();
  const FrameImages img = renderer.readback(true);
  const std::vector<ObjectMetrics> gpu = renderer.objectMetrics();
  test::expectValidationClean(renderer.validationMessages());
  EXPECT_EQ(gpu.size(), scene.objects.size());
  if (gpu.size() != scene.objects.size()) return 0;
  std::vector<uint32_t> detailed(scene.objects.size()), ambiguous(scene.objects.size());
  detailedPixels(img, w, h, s.rayTracing.maxRoughness, detailed, ambiguous);
  std::vector<select::Coverage> cov(scene.objects.size());
  std::vector<Classified> classes(scene.objects.size());
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t pixel = size_t(y) * w + x;
      const uint32_t id = img.objectIds[pixel];
      if (id == 0xFFFFFFFFu) continue;
      ++cov[id].pixels;
      cov[id].sumX += x;
      cov[id].sumY += y;
      const uint32_t c = pixelClasses(img, pixel, s.rayTracing.maxRoughness);
      classes[id].reflection += c & 1u;
      classes[id].refraction += c >> 1;
    }
  size_t visible = 0;
  for (const Object& o : scene.objects) {
    const std::string name = scene.path.filename().string() + " object " + std::to_string(o.id) + " '" + o.name + "'";
    const float distance = glm::length(0.5f * (o.boundsMin + o.boundsMax) - camera.position);
    const select::ObjectParams params = select::objectParams(scene, o, s.rayTracing.maxRoughness);
    const select::Metrics cpu = select::objectMetrics(cov[o.id], w, h, distance, camera.znear, params, false);
    const ObjectMetrics& g = gpu[o.id];
    EXPECT_EQ(g.pixels, cov[o.id].pixels) << name;
    EXPECT_EQ(g.reflectionPixels, classes[o.id].reflection) << name;
    EXPECT_EQ(g.refractionPixels, classes[o.id].refraction) << name;
    EXPECT_LE(std::abs(int64_t(g.detailedPixels) - int64_t(detailed[o.id])), int64_t(ambiguous[o.id])) << name << ": detailed pixels";
    if (classified) {
      classified->reflection += g.reflectionPixels;
      classified->refraction += g.refractionPixels;
      classified->detailed += g.detailedPixels;
    }
    visible += g.pixels > 0;
    const float slackV = cpu.A / cpu.D * kCentroidSlack;
    expectNear(g.A, cpu.A, 1e-6f, 0.0f, name + " A");
    expectNear(g.P, cpu.P, 1e-5f, kCentroidSlack, name + " P");
    expectNear(g.D, cpu.D, 1e-5f, 0.0f, name + " D");
    expectNear(g.V, cpu.V, 1e-4f, slackV, name + " V");
    expectNear(g.C, cpu.C, 1e-4f, slackV * params.Q, name + " C");
    expectNear(g.R, cpu.R, 1e-4f, slackV * params.K, name + " R");
    EXPECT_EQ(g.candidate, cpu.candidate) << name;
  }
  EXPECT_GT(visible, 0u) << scene.path.filename() << ": the camera should see something";
  size_t crowded = 0;
  for (const std::set<uint32_t>& tile : test::objectsPerTile(img.objectIds, w, h)) crowded += tile.size() > 3;
  return crowded;
}

TEST(CoverageGpu, MatchesTheCpuReferenceOnTheDefaultScene) {
  const Scene scene = loadScene(test::defaultScenePath());
  Classified classified;
  checkScene(scene, defaultCamera(scene, 1.5f), 240, 160, &classified);
  EXPECT_GT(classified.reflection, 0u) << "the court's mirrors and chrome need reflection rays";
  EXPECT_GT(classified.refraction, 0u) << "the court's glass needs refraction rays";
  EXPECT_GT(classified.detailed, 0u) << "the court's small chrome and glass spheres are detailed at this size";
  EXPECT_LT(classified.detailed, classified.reflection) << "its flat mirror panel is not";
  // Close up and at an angle: objects cut by the screen edge, some behind the camera; an odd
  // size, so that edge tiles are partial with objects in them.
  Camera close = defaultCamera(scene, 1.5f);
  close.position = glm::mix(close.position, close.target, 0.7f);
  checkScene(scene, close, 241, 161);
}

TEST(CoverageGpu, MatchesTheCpuReferenceOnACrowdedGrid) {
  // 3000 cubes at 203x125: many tiles show more than three objects, and odd partial tiles
  // at the right and bottom edges (the pass gathers 2x2 quads and skips texels past them).
  const Scene scene = cubeGridScene(3000);
  const size_t crowded = checkScene(scene, defaultCamera(scene, 203.0f / 125.0f), 203, 125);
  EXPECT_GT(crowded, 20u) << "the grid should crowd some tiles";
}

TEST(CoverageGpu, MatchesTheCpuReferenceOnTheCiScenes) {
  RB_REQUIRE_SHARED_SCENES();
  for (const auto& path : test::manifestScenes("ci")) {
    const Scene scene = loadScene(path);
    checkScene(scene, defaultCamera(scene, 4.0f / 3.0f), 96, 72);
  }
}

}  // namespace
}  // namespace raybudget

namespace raybudget {
namespace {

// K, Q and I changed at run time (the editor's sliders) reach the next frame's C = V·Q and
// R = (S·I + V)·K, survive a restart of the selection, and bad values change nothing.
TEST(ObjectParams, ChangedAtRunTimeTheNextFrameUsesThem) {
  const Scene scene = loadScene(test::defaultScenePath());
  RenderSettings s = test::settingsFor(Policy::Paper, 160, 96);
  s.budgetMs = 1000.0f;
  s.learnTimeScale = false;
  s.objectMetrics = true;
  Renderer r(scene, s);
  const Camera cam = defaultCamera(scene, r.aspect());
  auto frame = [&] {
    r.render(cam);
    r.finish();
    return r.objectMetrics();
  };
  const std::vector<ObjectMetrics> before = frame();
  size_t i = 0;
  while (i < before.size() && before[i].pixels == 0) ++i;
  ASSERT_LT(i, before.size()) << "some object is on screen";
  RayBudgetParams p;
  p.importanceK = 3.0f;
  p.raysQ = 7.0f;
  p.hysteresisI = 0.0f;
  r.setObjectParams(uint32_t(i), p);
  const RayBudgetParams set = r.objectParams(uint32_t(i));
  EXPECT_EQ(set.importanceK, 3.0f);
  EXPECT_EQ(set.raysQ, 7.0f);
  EXPECT_EQ(set.hysteresisI, 0.0f);
  const std::vector<ObjectMetrics> after = frame();
  EXPECT_EQ(after[i].V, before[i].V) << "the same view";
  EXPECT_EQ(after[i].C, after[i].V * 7.0f);
  EXPECT_EQ(after[i].R, after[i].V * 3.0f) << "I = 0: S no longer counts";
  RayBudgetParams bad = p;
  bad.importanceK = std::nanf("");
  try {
    r.setObjectParams(uint32_t(i), bad);
    ADD_FAILURE() << "a NaN K was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("object " + std::to_string(i)), std::string::npos) << e.what();
  }
  EXPECT_THROW(r.setObjectParams(uint32_t(scene.objects.size()), p), Error);
  EXPECT_EQ(r.objectParams(uint32_t(i)).importanceK, 3.0f) << "a refused value changes nothing";
  r.restartSelection(Policy::Paper, 1000.0f);
  const std::vector<ObjectMetrics> restarted = frame();
  EXPECT_EQ(restarted[i].C, restarted[i].V * 7.0f) << "a restart keeps the edited values";
  test::expectValidationClean(r.validationMessages());
}

// On a still view the coverage pass keeps the frame before's counts (RenderSettings::
// reuseStillCoverage) and computes only the objects' metrics: every frame's metrics, selection
// and image are those of counting again; the first frame after a change of view counts, and so
// does the first after a restart of the selection.
TEST(CoverageGpu, AStillViewKeepsTheFrameBeforesCountsAndSelectsAlike) {
  const Scene scene = loadScene(test::defaultScenePath());
  RenderSettings s = test::settingsFor(Policy::Benefit, 192, 112);
  s.rayTracing.rate = ItemRate::Auto;
  s.learnTimeScale = false;  // the same selection in both runs: no timing, no deadline
  s.budgetMs = 4.0f;
  s.objectMetrics = true;
  const Camera still = defaultCamera(scene, 192.0f / 112.0f);
  Camera moved = still;
  moved.position.x += 0.25f;
  const std::vector<Camera> path = {still, still, still, still, moved, moved, moved};
  auto run = [&](bool reuse) {
    RenderSettings r = s;
    r.reuseStillCoverage = reuse;
    Renderer renderer(scene, r, test::kCheckSelection);
    std::vector<FrameTiming> timings;
    std::vector<std::vector<ObjectMetrics>> metrics;
    for (const Camera& c : path) {
      for (const FrameTiming& t : renderer.render(c)) timings.push_back(t);
      for (const FrameTiming& t : renderer.finish()) timings.push_back(t);
      metrics.push_back(renderer.objectMetrics());
    }
    // A restart, on the same view.
    for (const FrameTiming& t : renderer.restartSelection(Policy::Density, 4.0f)) timings.push_back(t);
    for (const FrameTiming& t : renderer.render(moved)) timings.push_back(t);
    for (const FrameTiming& t : renderer.finish()) timings.push_back(t);
    metrics.push_back(renderer.objectMetrics());
    test::expectValidationClean(renderer.validationMessages());
    return std::tuple(timings, metrics, renderer.readback().ldrRgba8);
  };
  const auto [reusedTimings, reusedMetrics, reusedImage] = run(true);
  const auto [countedTimings, countedMetrics, countedImage] = run(false);
  ASSERT_EQ(reusedTimings.size(), path.size() + 1);
  const std::vector<bool> expected = {false, true, true, true, false, true, true, false};
  for (size_t f = 0; f < reusedTimings.size(); ++f) {
    EXPECT_EQ(reusedTimings[f].coverageReused, expected[f]) << "frame " << f;
    EXPECT_FALSE(countedTimings[f].coverageReused) << "frame " << f;
    EXPECT_TRUE(reusedTimings[f].selectionMatchesCpu.value_or(false)) << "frame " << f;
    EXPECT_EQ(reusedTimings[f].selectedObjects, countedTimings[f].selectedObjects) << "frame " << f;
    EXPECT_EQ(reusedTimings[f].selectedValue, countedTimings[f].selectedValue) << "frame " << f;
  }
  for (size_t f = 0; f < reusedMetrics.size(); ++f) {
    ASSERT_EQ(reusedMetrics[f].size(), countedMetrics[f].size());
    for (size_t o = 0; o < reusedMetrics[f].size(); ++o) {
      const ObjectMetrics &a = reusedMetrics[f][o], &b = countedMetrics[f][o];
      EXPECT_EQ(a.pixels, b.pixels) << "frame " << f << ", object " << o;
      EXPECT_EQ(a.reflectionPixels, b.reflectionPixels) << "frame " << f << ", object " << o;
      EXPECT_EQ(a.refractionPixels, b.refractionPixels) << "frame " << f << ", object " << o;
      EXPECT_EQ(a.R, b.R) << "frame " << f << ", object " << o;
      EXPECT_EQ(a.C, b.C) << "frame " << f << ", object " << o;
      EXPECT_EQ(a.selected, b.selected) << "frame " << f << ", object " << o;
    }
  }
  EXPECT_EQ(reusedImage, countedImage) << "the same frames";
}

}  // namespace
}  // namespace raybudget
