// Reduced ray rates (RayTracingSettings::rate): items traced on a checkerboard or one pixel per
// 2x2 quad, the rest filled by a joint bilateral filter from traced neighbours on the same
// object, across tiles: reflections and refractions in a pass of their own after the effects
// pass (shaders/include/effect_fill.glsl), shadows in the lighting pass (include/shadow_fill.glsl). The fill
// never takes another object's values; a flat mirror at 1/4 stays close to its full-rate
// image, and so do shadows; a lower rate traces fewer rays.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "support/procedural.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

// The spatial fill alone: the temporal fill (tests/temporal_fill_test.cpp) would show the still
// camera's earlier traced pixels.
RenderSettings reflectionsOnly(ItemRate rate, uint32_t w, uint32_t h) {
  RenderSettings s = test::settingsFor(Policy::All, w, h);
  s.rayTracing.rate = rate;
  s.rayTracing.temporalFill = false;
  s.rayTracing.shadows = false;
  s.rayTracing.refractions = false;
  s.skyIntensity = 0.0f;
  return s;
}

TEST(Rates, TheFillNeverReadsAcrossObjectIds) {
  const Scene scene = test::twoMirrors();
  Camera cam;
  cam.position = {0.0f, 4.0f, 4.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  const std::vector<Camera> frames(3, cam);  // the third frame: a turn of the rotation past the first
  const test::RenderedFrames full = test::renderFrames(scene, reflectionsOnly(ItemRate::Full, 256, 192), frames);
  for (ItemRate rate : {ItemRate::Half, ItemRate::Quarter, ItemRate::Sixteenth}) {
    const test::RenderedFrames reduced = test::renderFrames(scene, reflectionsOnly(rate, 256, 192), frames);
    size_t left = 0, right = 0, filledLeft = 0, foreign = 0;
    for (size_t p = 0; p < full.images.objectIds.size(); ++p) {
      const uint32_t id = full.images.objectIds[p];
      if (id > 1) continue;
      const uint8_t* c = &reduced.images.ldrRgba8[p * 4];
      const uint8_t* f = &full.images.ldrRgba8[p * 4];
      // The other mirror's colour: green on the left one, red on the right one.
      const int other = id == 0 ? c[1] - f[1] : c[0] - f[0];
      foreign += other > 8 ? 1 : 0;
      (id == 0 ? left : right) += 1;
      filledLeft += id == 0 && c[0] >= f[0] / 2 ? 1 : 0;
    }
    ASSERT_GT(left, 1000u);
    ASSERT_GT(right, 1000u);
    EXPECT_EQ(foreign, 0u) << itemRateName(rate) << ": pixels showing the other mirror's reflection";
    EXPECT_GT(filledLeft, left * 9 / 10) << itemRateName(rate) << ": the untraced pixels are filled from their own mirror";
  }
}

// Two coplanar grey floors (objects 0 and 1, touching at x = 0) under a sun straight above, and
// a thin board hovering over the left floor's edge: its shadow is a line on the left floor
// along x = 0. The shadow map (16 texels) misses the board, which lies between its texel
// centres, so the map lights both floors alike and the rays correct the line darker. At 1/4
// and 1/16 the shadow fill (include/shadow_fill.glsl) fills a right-floor pixel from right-floor
// neighbours alone: never darker than both the traced and the map's visibility there, which a
// left-floor neighbour's correction would make it (the map guides no neighbour out here).
TEST(Rates, TheShadowFillNeverReadsAcrossObjectIds) {
  Scene scene;
  Material grey;
  grey.metallic = 0.0f;
  grey.baseColorFactor = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
  for (float x : {-1.0f, 1.0f}) test::addObject(scene, test::quad(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, 0.0f)), grey);
  const glm::mat4 board = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-0.03f, 1.2f, 0.0f)), glm::vec3(0.03f, 1.0f, 1.0f));
  test::addObject(scene, test::quad(1.0f), board, grey);
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  scene.lights = {sun};
  Camera cam;
  cam.position = {0.0f, 3.0f, 3.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  auto render = [&](Policy policy, ItemRate rate) {
    RenderSettings s = test::settingsFor(policy, 256, 192);
    s.rayTracing.rate = rate;
    s.rayTracing.reflections = false;
    s.rayTracing.refractions = false;
    s.shadowMapSize = 16;
    s.skyIntensity = 0.0f;
    // The second frame: 1/4 and 1/16 trace odd columns, so a right-floor pixel at the boundary
    // (an even column) is filled with a traced left-floor pixel beside it.
    return test::renderFrames(scene, s, {cam, cam});
  };
  const test::RenderedFrames full = render(Policy::All, ItemRate::Full), none = render(Policy::None, ItemRate::Full);
  auto luminance = [](const test::RenderedFrames& r, size_t p) { return int(r.images.ldrRgba8[p * 4 + 1]); };
  size_t corrected[2] = {0, 0};  // pixels per floor where the rays change the map's shadow
  for (size_t p = 0; p < full.images.objectIds.size(); ++p) {
    const uint32_t id = full.images.objectIds[p];
    if (id <= 1 && std::abs(luminance(full, p) - luminance(none, p)) > 16) ++corrected[id];
  }
  ASSERT_GT(corrected[0], 100u) << "the map should miss the board's shadow on the left floor";
  ASSERT_EQ(corrected[1], 0u) << "the right floor should be lit alike by the map and the rays";
  for (ItemRate rate : {ItemRate::Quarter, ItemRate::Sixteenth}) {
    const test::RenderedFrames reduced = render(Policy::All, rate);
    size_t foreign = 0;
    for (size_t p = 0; p < full.images.objectIds.size(); ++p)
      if (full.images.objectIds[p] == 1 && luminance(reduced, p) < std::min(luminance(full, p), luminance(none, p)) - 16) ++foreign;
    EXPECT_EQ(foreign, 0u) << itemRateName(rate) << ": right-floor pixels darkened by the left floor's corrections";
  }
}

// On the default scene's mirror panel (which reflects small, detailed objects), 1/4 rate keeps
// over half of what tracing adds over the environment fallback and 1/2 about two thirds (mean
// display difference from full rate, as the benefit measures it; measured 0.039 and 0.023
// against the fallback's 0.088 at 320x192, the spatial fill alone), and each halving of the rate traces about half
// the rays. 1/16 keeps little of this mirror's detail at this size (0.070: its samples lie
// four pixels apart), less than of the smoother reflections the selection's keep shares were
// measured on (shared/selection.h).
TEST(Rates, AFlatMirrorAtAQuarterStaysCloseToFullRate) {
  const Scene scene = loadScene(test::defaultScenePath());
  const uint32_t mirror = test::objectNamed(scene, "mirror_panel");
  ASSERT_NE(mirror, test::kNoObjectNamed);
  const Camera cam = defaultCamera(scene, 320.0f / 192.0f);
  const std::vector<Camera> frames(3, cam);
  auto render = [&](Policy policy, ItemRate rate) {
    RenderSettings s = test::settingsFor(policy, 320, 192);
    s.rayTracing.rate = rate;
    s.rayTracing.temporalFill = false;  // the spatial fill alone
    return test::renderFrames(scene, s, frames);
  };
  const test::RenderedFrames full = render(Policy::All, ItemRate::Full), half = render(Policy::All, ItemRate::Half),
                             quarter = render(Policy::All, ItemRate::Quarter), sixteenth = render(Policy::All, ItemRate::Sixteenth),
                             none = render(Policy::None, ItemRate::Full);
  auto mirrorDifference = [&](const test::RenderedFrames& r) {
    double sum = 0.0;
    size_t pixels = 0;
    for (size_t p = 0; p < full.images.objectIds.size(); ++p) {
      if (full.images.objectIds[p] != mirror) continue;
      for (int c = 0; c < 3; ++c) sum += std::abs(double(r.images.ldrRgba8[p * 4 + c]) - double(full.images.ldrRgba8[p * 4 + c])) / 255.0;
      ++pixels;
    }
    return pixels ? sum / double(3 * pixels) : 0.0;
  };
  const double atQuarter = mirrorDifference(quarter), atHalf = mirrorDifference(half), atSixteenth = mirrorDifference(sixteenth),
               fallback = mirrorDifference(none);
  const uint32_t raysFull = full.timings.back().raysTraced, raysHalf = half.timings.back().raysTraced, raysQuarter = quarter.timings.back().raysTraced,
                 raysSixteenth = sixteenth.timings.back().raysTraced;
  std::printf("mirror panel, mean display difference from full rate: half %.4f, quarter %.4f, sixteenth %.4f, fallback %.4f; rays %u / %u / %u / %u\n",
              atHalf, atQuarter, atSixteenth, fallback, raysFull, raysHalf, raysQuarter, raysSixteenth);
  EXPECT_GT(fallback, 0.02) << "the mirror's fallback should be visibly wrong";
  EXPECT_LT(atQuarter, 0.5 * fallback) << "a quarter of the rays keeps over half of what tracing the mirror adds";
  EXPECT_LT(atHalf, 0.35 * fallback);
  EXPECT_LT(raysHalf, raysFull * 6 / 10);
  EXPECT_LT(raysQuarter, raysFull * 35 / 100);
  EXPECT_LT(atSixteenth, 0.9 * fallback) << "a sixteenth of the rays keeps some of what tracing the mirror adds";
  EXPECT_GT(atSixteenth, atQuarter) << "fewer rays, a blurrier reflection";
  EXPECT_LT(raysSixteenth, raysFull * 12 / 100);
}

// Shadows alone on the default scene: the fill corrects the shadow map by the traced
// neighbours' difference from it (include/shadow_fill.glsl), so at 1/4 and 1/2 the image stays closer
// to full rate than the maps are: with coarse (128 texel) maps (measured 0.0018 and 0.0032
// against the maps' 0.0089 at 320x192) and with the default 1024-texel ones (0.0008 and 0.0014
// against 0.0016), where filling the visibility itself lost to the maps (0.0019 and 0.0031: the
// blocky edges of thin shadows).
TEST(Rates, ShadowsAtReducedRatesStayCloserToFullRateThanShadowMaps) {
  const Scene scene = loadScene(test::defaultScenePath());
  const std::vector<Camera> frames(3, defaultCamera(scene, 320.0f / 192.0f));
  for (uint32_t mapSize : {128u, 1024u}) {
    auto render = [&](Policy policy, ItemRate rate) {
      RenderSettings s = test::settingsFor(policy, 320, 192);
      s.rayTracing.rate = rate;
      s.rayTracing.reflections = false;
      s.rayTracing.refractions = false;
      s.shadowMapSize = mapSize;
      s.rayTracing.temporalFill = false;  // the spatial fill alone (temporal_fill_test.cpp has the history)
      return test::renderFrames(scene, s, frames);
    };
    const test::RenderedFrames full = render(Policy::All, ItemRate::Full), half = render(Policy::All, ItemRate::Half),
                               quarter = render(Policy::All, ItemRate::Quarter), none = render(Policy::None, ItemRate::Full);
    auto difference = [&](const test::RenderedFrames& r) {
      double sum = 0.0;
      for (size_t i = 0; i < full.images.ldrRgba8.size(); ++i)
        if (i % 4 != 3) sum += std::abs(double(r.images.ldrRgba8[i]) - double(full.images.ldrRgba8[i])) / 255.0;
      return sum / double(full.images.ldrRgba8.size() / 4 * 3);
    };
    const double atHalf = difference(half), atQuarter = difference(quarter), maps = difference(none);
    std::printf("shadows, mean display difference from full rate: half %.4f, quarter %.4f, %u-texel shadow maps %.4f\n", atHalf, atQuarter,
                mapSize, maps);
    EXPECT_GT(maps, 0.001) << mapSize << "-texel shadow maps should differ visibly from traced shadows";
    EXPECT_LT(atQuarter, (mapSize == 128 ? 0.7 : 0.95) * maps) << mapSize << "-texel maps";
    EXPECT_LT(atHalf, 0.7 * atQuarter) << mapSize << "-texel maps";
  }
}

// The two mirrors alone (reflecting the sky) under a sun, seen from above, with `benefit`
// choosing rates per item at a fixed time scale; unbudgeted, and with the candidates' summed
// cost in the stats (the budgets below are shares of it).
struct MirrorsUnderSun {
  Scene scene;
  RenderSettings settings;
  Camera camera;
};
MirrorsUnderSun mirrorsUnderSun() {
  MirrorsUnderSun m{test::twoMirrors(), test::settingsFor(Policy::Benefit, 256, 192), {}};
  m.scene.objects.resize(2);
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  m.scene.lights = {sun};
  m.settings.rayTracing.rate = ItemRate::Auto;
  m.settings.learnTimeScale = false;
  m.settings.optimalBound = true;
  m.settings.budgetMs = 1e6f;
  m.camera.position = {0.0f, 4.0f, 4.0f};
  m.camera.target = {0.0f, 0.0f, 0.0f};
  return m;
}

// Rates chosen per item on two mirrors under a sun: more rate segments than three per object
// (shadows one, reflections three), every frame's segments, costs, values, levels and rates
// equal to the CPU reference under a budget that binds; frames after one at a reduced rate
// price the item's segments from the cost its skipped pixels took (learned on the GPU, the CPU
// reference the same bit for bit), which is below what its traced pixels cost.
TEST(Rates, ChosenPerItemEqualTheCpuReferenceOnAllMirrors) {
  auto [scene, s, cam] = mirrorsUnderSun();
  const test::RenderedFrames all = test::renderFrames(scene, s, std::vector<Camera>(4, cam), test::kCheckSelection);
  // A first frame prices the items from priors: a third of that binds (later frames learn
  // cheaper costs).
  ASSERT_GT(all.timings.front().candidatesMs, 0.0);
  s.budgetMs = float(all.timings.front().candidatesMs / 3.0);
  const test::RenderedFrames part = test::renderFrames(scene, s, {cam}, test::kCheckSelection);
  // Items learn from their clock ticks only where the time scale is learned too (with the
  // prior's, in traversal work units, they learn traversal work: RB_ITEM_COSTS_UNTIMED).
  s.learnTimeScale = true;
  // Without the stage's deadline: under a busy machine it cut these frames' fill short, which
  // then learned nothing of what a skipped pixel costs.
  s.stageDeadline = false;
  const test::RenderedFrames later = test::renderFrames(scene, s, std::vector<Camera>(3, cam), test::kCheckSelection);
  for (const test::RenderedFrames* r : {&all, &part, &later})
    for (const FrameTiming& t : r->timings) {
      EXPECT_TRUE(t.selectionMatchesCpu.value_or(false)) << "frame " << t.frame;
      EXPECT_TRUE(t.costsMatchCpu.value_or(false)) << "frame " << t.frame;
      // The bound is over whole options: a partial item's share of its tiles adds value beyond
      // it, as a fractional knapsack's does (docs/SELECTION.md).
      if (t.partialShare == 0.0f) {
        EXPECT_LE(t.selectedValue, t.optimalValueBound * (1.0 + 1e-5)) << "the multiple-choice bound holds, frame " << t.frame;
      }
    }
  uint32_t reduced = 0;
  for (const ObjectMetrics& m : part.metrics)
    for (int e = 0; e < 3; ++e) reduced += ((m.selectedItems >> e) & 1u) && m.itemRate[size_t(e)] != ItemRate::Full;
  EXPECT_GT(reduced, 0u) << "under a third of the budget some mirror should be traced at a reduced rate";
  // A filled pixel costs less than a traced one: on an idle machine 0.3-0.6 of it on these
  // mirrors, whose rays mostly leave for the sky; the fill is timed on one workgroup in four, so
  // on a busy machine one preempted sample can lift a small mirror's past it (CI: 3.51 against
  // 2.43), hence twice as the bound for each and below for one.
  uint32_t learnedFill = 0, cheaperFill = 0;
  for (const ObjectMetrics& m : later.metrics) {
    const float fill = m.itemFillPerPixel[1];  // reflections
    if (fill <= 0.0f) continue;
    ++learnedFill;
    cheaperFill += fill < m.itemCostPerPixel[1];
    std::printf("a mirror's reflections: %.2f units per filled pixel, %.2f per traced pixel\n", fill, m.itemCostPerPixel[1]);
    EXPECT_LT(fill, 2.0f * m.itemCostPerPixel[1]) << "a filled pixel costs less than a traced one";
  }
  EXPECT_GT(learnedFill, 0u) << "a mirror traced at a reduced rate learns what its skipped pixels cost";
  EXPECT_GT(cheaperFill, 0u) << "a filled pixel costs less than a traced one";
}

// The selected items' rates in a frame's metrics: how many at 1/16, 1/4 and full.
std::map<ItemRate, uint32_t> selectedRates(const std::vector<ObjectMetrics>& metrics) {
  std::map<ItemRate, uint32_t> n;
  for (const ObjectMetrics& m : metrics)
    for (size_t e = 0; e < 3; ++e)
      if ((m.selectedItems >> e) & 1u) ++n[m.itemRate[e]];
  return n;
}

// `cameras` rendered after the items' costs were learned without a budget (the first four),
// at a third of what they cost then; every frame's selection and costs the CPU reference's.
std::map<ItemRate, uint32_t> ratesAtAThirdOfTheCost(const Scene& scene, RenderSettings s, const std::vector<Camera>& cameras) {
  s.objectMetrics = true;
  Renderer r(scene, s, test::kCheckSelection);
  std::vector<FrameTiming> timings;
  for (size_t f = 0; f < cameras.size(); ++f) {
    if (f == 4) {
      for (const FrameTiming& t : r.finish()) timings.push_back(t);
      r.setBudget(float(timings.back().candidatesMs / 3.0));
    }
    for (const FrameTiming& t : r.render(cameras[f])) timings.push_back(t);
  }
  for (const FrameTiming& t : r.finish()) timings.push_back(t);
  for (const FrameTiming& t : timings) {
    EXPECT_TRUE(t.selectionMatchesCpu.value_or(false)) << "frame " << t.frame;
    EXPECT_TRUE(t.costsMatchCpu.value_or(false)) << "frame " << t.frame;
  }
  test::expectValidationClean(r.validationMessages());
  return selectedRates(r.objectMetrics());
}

// On a still view the temporal fill carries each pixel a rate traced until the rate traces it
// again, so a reduced rate keeps nearly all of full rate once the view has stayed still for its
// period (shared/selection.h's RB_FILL_QUALITY_STILL): on a moving view `benefit` prices the
// rates at the priors; after 15 still frames it trades full rate and 1/4 (no longer on the
// hull) for 1/16 on more items (the court at 192x112: 43-48 items, 36-40 at 1/16,
// against 15-20 and 0-2).
TEST(Rates, AStillViewTradesDearRatesForTheCheapestOnMoreItems) {
  const Scene scene = loadScene(test::defaultScenePath());
  RenderSettings s = test::settingsFor(Policy::Benefit, 192, 112);
  s.rayTracing.rate = ItemRate::Auto;
  s.learnTimeScale = false;
  s.optimalBound = true;  // (the candidates' summed cost in the stats)
  s.budgetMs = 1e6f;
  const std::vector<Camera> still(20, defaultCamera(scene, 192.0f / 112.0f));
  std::vector<Camera> moving = still;  // a view never still two frames in a row: the priors
  for (size_t f = 1; f < moving.size(); f += 2) moving[f].position.x += 1e-3f;
  std::map<ItemRate, uint32_t> moved = ratesAtAThirdOfTheCost(scene, s, moving), stayed = ratesAtAThirdOfTheCost(scene, s, still);
  for (auto [rate, n] : moved) std::printf("a moving view: %u at %s\n", n, itemRateName(rate));
  for (auto [rate, n] : stayed) std::printf("a still view: %u at %s\n", n, itemRateName(rate));
  EXPECT_EQ(stayed[ItemRate::Quarter], 0u) << "1/4 lies under the line from 1/16 to full on a still view";
  EXPECT_GT(stayed[ItemRate::Sixteenth], moved[ItemRate::Sixteenth]);
}

// The partial item (docs/SELECTION.md): where the walk leaves budget that pays for a share of the
// next item's 1/16, that item is traced on the 8x8 tiles whose hash falls below the share and
// on no other, and the GPU's choice (item and share) is the CPU reference's. The hash is
// include/probe.glsl's tileTurn, copied here as the oracle.
bool partialTile(uint32_t tx, uint32_t ty, double share) {
  uint32_t h = (tx * 0x8DA6B343u) ^ (ty * 0xD8163841u);
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  return float(h >> 8) * (1.0f / 16777216.0f) < float(share);
}

TEST(Rates, ThePartialItemIsTracedOnItsShareOfTilesAlone) {
  auto [scene, s, cam] = mirrorsUnderSun();
  s.rayTracing.shadows = false;  // the mirrors' reflections alone: two items
  s.objectMetrics = true;
  // A first frame prices the items from their priors, the same in every renderer: budgets are
  // shares of that frame's candidates (both mirrors' segments, so 1/16 of one is about 0.11).
  const test::RenderedFrames all = test::renderFrames(scene, s, {cam}, test::kCheckSelection);
  const double candidates = all.timings.front().candidatesMs;
  ASSERT_GT(candidates, 0.0);
  uint32_t partialFrames = 0;
  for (double fraction : {0.02, 0.04, 0.07, 0.1, 0.15, 0.25}) {
    s.budgetMs = float(fraction * candidates);
    Renderer renderer(scene, s, test::kCheckSelection);
    std::vector<FrameTiming> timings = renderer.render(cam);
    for (const FrameTiming& t : renderer.finish()) timings.push_back(t);
    const FrameImages img = renderer.readback(true);  // with the object IDs and the traced mask
    const std::vector<ObjectMetrics> metrics = renderer.objectMetrics();
    test::expectValidationClean(renderer.validationMessages());
    ASSERT_EQ(timings.size(), 1u);
    EXPECT_TRUE(timings[0].selectionMatchesCpu.value_or(false)) << "fraction " << fraction;
    const double share = timings[0].partialShare;
    if (share <= 0.0) continue;
    ++partialFrames;
    EXPECT_GE(share, 0.125);
    EXPECT_LT(share, 1.0);
    // Per object: its pixels traced for reflections inside and outside the share's tiles, and
    // its pixels outside them. The partial item's traced pixels all lie inside, though it
    // covers tiles outside.
    std::map<uint32_t, std::array<size_t, 3>> counts;  // traced in, traced out, covered out
    for (uint32_t y = 0; y < s.height; ++y)
      for (uint32_t x = 0; x < s.width; ++x) {
        const size_t i = size_t(y) * s.width + x;
        if (img.objectIds[i] == 0xFFFFFFFFu) continue;
        const bool in = partialTile(x / 8, y / 8, share);
        std::array<size_t, 3>& c = counts[img.objectIds[i]];
        if (img.tracedMask[i] & core::kTracedReflections) ++c[in ? 0 : 1];
        if (!in) ++c[2];
      }
    uint32_t confined = 0, confinedId = 0;
    for (const auto& [id, c] : counts)
      if (c[0] > 0 && c[1] == 0 && c[2] > 0) ++confined, confinedId = id;
    EXPECT_EQ(confined, 1u) << "fraction " << fraction << ", share " << share;
    // The object metrics name it: its reflections on that share of its tiles.
    ASSERT_GT(metrics.size(), confinedId);
    EXPECT_EQ(metrics[confinedId].itemTileShare[1], float(share));
    for (size_t id = 0; id < metrics.size(); ++id)
      if (id != confinedId) {
        EXPECT_EQ(metrics[id].itemTileShare[1], 1.0f) << "object " << id;
      }
  }
  EXPECT_GE(partialFrames, 1u) << "no budget left a share of a mirror to trace";
}

// With rates in the frame the trace passes hand a tile's pixels out in another order (1/16's
// first, shaders/include/tile_pixel.glsl): a permutation, so with every item chosen at full
// rate the image is full RT's, pixel for pixel.
TEST(Rates, HandingOutPixelsForRatesLeavesNoneOut) {
  const Scene scene = loadScene(test::defaultScenePath());
  const std::vector<Camera> frames(3, defaultCamera(scene, 320.0f / 192.0f));
  RenderSettings all = test::settingsFor(Policy::All, 320, 192);
  RenderSettings chosen = test::settingsFor(Policy::Benefit, 320, 192);
  chosen.rayTracing.rate = ItemRate::Auto;
  chosen.rayTracing.classifyShadows = false;  // as `all`: every shadow ray traced, to the light
  chosen.rayTracing.shortenShadowRays = false;
  chosen.probeShare = 0.0f;
  chosen.budgetMs = 1e6f;
  const test::RenderedFrames reference = test::renderFrames(scene, all, frames), reordered = test::renderFrames(scene, chosen, frames);
  uint32_t reduced = 0;
  for (const ObjectMetrics& m : reordered.metrics)
    for (int e = 0; e < 3; ++e) reduced += ((m.selectedItems >> e) & 1u) && m.itemRate[size_t(e)] != ItemRate::Full;
  ASSERT_EQ(reduced, 0u) << "under an unbounded budget every item is traced at full rate";
  size_t differing = 0;
  for (size_t i = 0; i < reference.images.ldrRgba8.size(); ++i) differing += reference.images.ldrRgba8[i] != reordered.images.ldrRgba8[i] ? 1 : 0;
  EXPECT_EQ(differing, 0u) << "channels differing from full RT's image";
}

TEST(Rates, UnknownRateNamesAreRefusedNamingTheChoices) {
  EXPECT_EQ(parseItemRate("quarter"), ItemRate::Quarter);
  EXPECT_EQ(parseItemRate("sixteenth"), ItemRate::Sixteenth);
  RenderSettings s;
  s.rayTracing.rate = ItemRate(9);  // an integer cast in, as from a host's configuration
  test::expectRefusedNaming(Scene{}, s, "rayTracing.rate");
  try {
    parseItemRate("third");
    FAIL() << "accepted an unknown rate";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("full, half, quarter"), std::string::npos) << e.what();
  }
}

// Restarting `renderer` at `rate` is refused with a raybudget::Error whose text holds `naming`.
void expectRestartRefusedNaming(Renderer& renderer, ItemRate rate, const std::string& naming) {
  try {
    renderer.restartSelection(Policy::Benefit, 4.0f, BenefitAblation::None, rate);
    ADD_FAILURE() << "restarted at " << itemRateName(rate) << " without the history it needs";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(naming), std::string::npos) << e.what();
  }
}

// The reflection and refraction fill reads the history of the pixels traced this frame, made
// only for a renderer made with a reduced rate: restarting one made at full rate with a reduced
// rate is refused with a clear error, not filled from an image that is not there; one made
// with a reduced rate restarts at any rate.
TEST(Rates, ARendererMadeAtFullRateRefusesToRestartAtAReducedOne) {
  auto [scene, s, cam] = mirrorsUnderSun();
  s.rayTracing.rate = ItemRate::Full;
  Renderer full(scene, s);
  expectRestartRefusedNaming(full, ItemRate::Auto, "RayTracingSettings::rate");
  full.restartSelection(Policy::Benefit, 4.0f, BenefitAblation::None, ItemRate::Full);
  s.rayTracing.rate = ItemRate::Quarter;
  Renderer reduced(scene, s);
  reduced.restartSelection(Policy::Benefit, 4.0f, BenefitAblation::None, ItemRate::Sixteenth);
  EXPECT_EQ(reduced.render(cam).size() + reduced.finish().size(), 1u);
}

// The same mirrors made rough: nothing reflects or refracts, so a reduced rate needs only the
// shadows' history (include/shadow_history.glsl), which a renderer made at full rate lacks; with
// ray-traced shadows off it needs none.
TEST(Rates, AShadowsOnlyRendererMadeAtFullRateRefusesAReducedRateForItsShadows) {
  auto [scene, s, cam] = mirrorsUnderSun();
  for (Material& m : scene.materials) m.roughness = 1.0f;
  s.rayTracing.rate = ItemRate::Full;
  Renderer full(scene, s);
  expectRestartRefusedNaming(full, ItemRate::Quarter, "shadow fill's history");
  s.rayTracing.shadows = false;
  Renderer unshadowed(scene, s);
  unshadowed.restartSelection(Policy::Benefit, 4.0f, BenefitAblation::None, ItemRate::Quarter);
  EXPECT_EQ(unshadowed.render(cam).size() + unshadowed.finish().size(), 1u);
  test::expectValidationClean(unshadowed.validationMessages());
}

}  // namespace
}  // namespace raybudget
