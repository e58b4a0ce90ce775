// Items per effect (`benefit`, `classified`): the GPU's per-item learning and selection equal
// their CPU references; the display error the trace passes measure equals the difference of
// the traced and fallback images; the shadow classifier saves rays and keeps the image.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "select/object_params.h"
#include "shared/config.h"
#include "shared/selection.h"
#include "support/procedural.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

using test::settingsFor;

// Per object, the display-space error of `traced` against `fallback` as the trace passes
// define it (the mean absolute difference of the sRGB-encoded channels), summed over the
// object's pixels, from the 8-bit images; and each object's pixel count.
void imageErrorPerObject(const FrameImages& traced, const FrameImages& fallback, size_t objects, std::vector<double>& error,
                         std::vector<uint32_t>& pixels) {
  error.assign(objects, 0.0);
  pixels.assign(objects, 0);
  for (size_t p = 0; p < traced.objectIds.size(); ++p) {
    const uint32_t id = traced.objectIds[p];
    if (id >= objects) continue;
    double d = 0.0;
    for (int c = 0; c < 3; ++c) d += std::abs(double(traced.ldrRgba8[p * 4 + c]) - double(fallback.ldrRgba8[p * 4 + c])) / 255.0;
    error[id] += d / 3.0;
    ++pixels[id];
  }
}

// A mirror under an emissive quad, a glass cube over an emissive floor, and a sphere casting
// a shadow on a lit plane: one item of each effect with a clear error to remove.
Scene itemScene() {
  Scene scene;
  const Material mirror = test::mirror();
  test::addObject(scene, test::quad(3.0f), glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f, 0.0f, 0.0f)), mirror);
  const Material glass = test::tintedGlass();
  test::addObject(scene, test::subdividedCube(1), glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 0.5f, 0.0f)), glass);
  Material emitter;  // a wall behind the scene, out of the sun's way: what the mirror reflects
  emitter.baseColorFactor = glm::vec4(0, 0, 0, 1);
  emitter.emissive = glm::vec3(2.0f, 0.5f, 0.2f);
  emitter.doubleSided = true;
  test::addObject(scene, test::quad(20.0f),
                  glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -12)) * glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0)), emitter);
  Material floor;  // lit, under everything: what the glass shows
  floor.baseColorFactor = glm::vec4(0.8f, 0.3f, 0.1f, 1.0f);
  floor.metallic = 0.0f;
  floor.roughness = 0.9f;
  test::addObject(scene, test::quad(20.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0)), floor);
  Material matte;
  matte.metallic = 0.0f;
  matte.roughness = 0.9f;
  test::addObject(scene, test::quad(3.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 3.0f)), matte);
  test::addObject(scene, test::subdividedCube(2), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.05f, 3.0f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.3f, 0.05f, 0.3f)), matte);
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  sun.intensity = 3.0f;
  scene.lights.push_back(sun);
  return scene;
}

Camera itemCamera() {
  Camera cam;
  cam.position = {0.0f, 6.0f, 7.0f};
  cam.target = {0.0f, 0.0f, 1.0f};
  return cam;
}

// Items' untraced prices learn the time of a ray their prior counts (a shadow ray per light at
// each traced pixel), apart from the objects' time per ray traced. Every shadow pixel traces
// here (no classifier) under one sun: the prior's rays are the rays traced plus the pixels
// facing away from it, so the time per prior ray lies at or a little under the time per ray
// traced, and the objects' time per ray stays unlearned.
TEST(Items, ItemsLearnTheTimeOfTheRaysTheirPriorCounts) {
  const Scene scene = itemScene();
  RenderSettings s = settingsFor(Policy::Benefit, 160, 120);
  s.rayTracing.reflections = false;
  s.rayTracing.refractions = false;
  s.rayTracing.classifyShadows = false;
  s.rayTracing.shortenShadowRays = false;
  s.probeShare = 0.0f;
  s.budgetMs = 1e6f;
  Renderer renderer(scene, s);
  std::vector<FrameTiming> timings;
  auto run = [&](int frames) {
    for (int f = 0; f < frames; ++f)
      for (const FrameTiming& t : renderer.render(itemCamera())) timings.push_back(t);
    for (const FrameTiming& t : renderer.finish()) timings.push_back(t);
  };
  run(6);
  // A budget everything fits in twice over: frames that use a quarter of their budget teach
  // the time scale (cost_model.cpp). From the median warm frame, not the last one: set from one
  // frame slowed by a busy machine, the budget let no frame teach it.
  std::vector<double> warm;
  for (size_t f = 2; f < timings.size(); ++f) warm.push_back(timings[f].rtStageMs());
  std::sort(warm.begin(), warm.end());
  ASSERT_FALSE(warm.empty());
  ASSERT_GT(warm[warm.size() / 2], 0.0);
  renderer.setBudget(float(2.0 * warm[warm.size() / 2]));
  timings.clear();
  run(16);  // more than the time scale's window (RecentMedian::kSize), so that it holds these frames alone
  const CostModel model = renderer.costModel();
  test::expectValidationClean(renderer.validationMessages());
  // The frames the model learns from (cost_model.cpp: predicted or measured work time at least
  // a quarter of the trace budget), up to the last 7 of them, the time scale's window: a machine
  // whose load changes during the run (the other tests beside this one) times the earlier
  // frames otherwise, and where it got faster the frames that no longer use a quarter of the
  // budget teach the model nothing (a learned time 1.44x the last 7 frames' median, with
  // another job on the 2 cores).
  std::vector<double> perTracedRay;
  for (const FrameTiming& t : timings) {
    const double workMs = std::max(t.predictedTraceMs, t.measuredTraceMs) - model.traceFixedMs;
    if (t.raysTraced > 0 && t.measuredTraceMs > model.traceFixedMs && workMs >= 0.25 * t.traceBudgetMs)
      perTracedRay.push_back((t.measuredTraceMs - model.traceFixedMs) / t.raysTraced);
  }
  ASSERT_GE(perTracedRay.size(), 3u);
  perTracedRay.erase(perTracedRay.begin(), perTracedRay.end() - std::min<ptrdiff_t>(7, ptrdiff_t(perTracedRay.size())));
  std::sort(perTracedRay.begin(), perTracedRay.end());
  const double median = perTracedRay[perTracedRay.size() / 2];
  EXPECT_EQ(model.msPerRay, 0.0) << "no object's ray was timed";
  EXPECT_GT(model.msPerItemRay, 0.7 * median) << "counted twice, it would halve";
  EXPECT_LT(model.msPerItemRay, 1.25 * median);
}

// The error each traced item removed, as the trace and lighting passes measured it, equals
// the per-object difference of the traced (`classified`: every item) and fallback (`none`)
// images: one effect at a time, so that each object's image difference is that item's.
TEST(Items, MeasuredErrorEqualsTheImageDifferenceAgainstTheFallback) {
  const Scene scene = itemScene();
  const Camera cam = itemCamera();
  for (uint32_t effect = 0; effect < RB_ITEMS_PER_OBJECT; ++effect) {
    RenderSettings s = settingsFor(Policy::Classified, 160, 120);
    s.skyIntensity = 0.1f;
    s.shadowMapSize = 64;  // coarse: its edges are visibly wrong
    s.rayTracing.shadows = effect == RB_ITEM_SHADOWS;
    s.rayTracing.reflections = effect == RB_ITEM_REFLECTIONS;
    s.rayTracing.refractions = effect == RB_ITEM_REFRACTIONS;
    const test::RenderedFrames traced = test::renderFrames(scene, s, {cam});
    s.policy = Policy::None;
    const test::RenderedFrames fallback = test::renderFrames(scene, s, {cam});
    std::vector<double> error;
    std::vector<uint32_t> pixels;
    imageErrorPerObject(traced.images, fallback.images, scene.objects.size(), error, pixels);
    double largest = 0.0;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
      const double measured = traced.metrics[i].itemError[effect];
      // 8-bit images: each channel within 1/255 of the shader's value.
      EXPECT_NEAR(measured, error[i], 0.02 * error[i] + pixels[i] / 255.0 + 1.0) << "effect " << effect << ", object " << i;
      for (uint32_t other = 0; other < RB_ITEMS_PER_OBJECT; ++other)
        if (other != effect) {
          EXPECT_EQ(traced.metrics[i].itemError[other], 0.0f) << "effect " << effect << ", object " << i;
        }
      largest = std::max(largest, measured / std::max(1u, pixels[i]));
    }
    EXPECT_GT(largest, 0.02) << "effect " << effect << ": some object's fallback should be visibly wrong";
  }
}

// Every frame of an orbit, with the time scale frozen: each item's learned work per pixel
// and benefit, its counters, S and traced pixels, and each item candidate's cost and value
// equal the CPU reference (cost_model.h), and the GPU selects exactly the items the CPU
// reference selects from the same candidates, under a budget that binds.
TEST(Items, BenefitLearningAndSelectionEqualTheCpuReference) {
  const Scene scene = loadScene(test::defaultScenePath());
  auto orbit = [&](float budgetMs, std::vector<ObjectMetrics>* last, BenefitAblation ablation = BenefitAblation::None,
                   ItemRate rate = ItemRate::Full) {
    RenderSettings s = settingsFor(Policy::Benefit, 320, 192);
    s.budgetMs = budgetMs;
    s.benefitAblation = ablation;
    s.rayTracing.rate = rate;
    s.learnTimeScale = false;
    s.objectMetrics = true;
    Renderer renderer(scene, s, test::kCheckSelection);
    const Camera start = defaultCamera(scene, renderer.aspect());
    std::vector<FrameTiming> t;
    for (uint32_t f = 0; f < 6; ++f)
      for (const FrameTiming& x : renderer.render(orbitCamera(start, f, 24))) t.push_back(x);
    for (const FrameTiming& x : renderer.finish()) t.push_back(x);
    test::expectValidationClean(renderer.validationMessages());
    for (const FrameTiming& f : t) {
      EXPECT_TRUE(f.selectionMatchesCpu.value_or(false)) << ablationName(ablation) << " T " << budgetMs << ", frame " << f.frame;
      EXPECT_TRUE(f.costsMatchCpu.value_or(false)) << ablationName(ablation) << " T " << budgetMs << ", frame " << f.frame;
    }
    if (last) *last = renderer.objectMetrics();
    return t;
  };
  const std::vector<FrameTiming> all = orbit(1e6f, nullptr);
  ASSERT_EQ(all.size(), 6u);
  ASSERT_GT(all.back().predictedTraceMs, 0.0);
  // An eighth of the unbudgeted frame's predicted cost: the items' costs come from clock
  // ticks, which a loaded machine inflates in one run and not the other, so the margin is wide.
  std::vector<ObjectMetrics> metrics;
  const std::vector<FrameTiming> part = orbit(float(all.back().predictedTraceMs / 8.0), &metrics);
  uint32_t binding = 0;
  for (size_t f = 0; f < part.size(); ++f) binding += part[f].selectedObjects > 0 && part[f].selectedObjects < all[f].selectedObjects;
  EXPECT_GE(binding, 3u) << "the budget should bind in most frames";
  uint32_t learned = 0;
  for (size_t i = 0; i < metrics.size(); ++i) {
    const glm::vec3 priors = select::itemPriors(scene, scene.objects[i]);
    for (int e = 0; e < 3; ++e) {
      const float b = metrics[i].itemBenefit[size_t(e)];
      EXPECT_TRUE(std::isfinite(b) && b >= 0.0f);
      learned += b != priors[e];
    }
  }
  EXPECT_GT(learned, 0u) << "traced items should have measured benefits";
  // The ablations' GPU paths equal their references too.
  for (BenefitAblation a : {BenefitAblation::NoCentrality, BenefitAblation::NoHysteresis, BenefitAblation::PriorOnly, BenefitAblation::NoProbe})
    orbit(float(all.back().predictedTraceMs / 4.0), nullptr, a);
  // So do reduced ray rates: the items' rates in the selection, their costs at the rate's
  // share, and what the trace passes count on the pixels traced.
  for (ItemRate r : {ItemRate::Half, ItemRate::Quarter, ItemRate::Auto}) {
    const std::vector<FrameTiming> frames = orbit(float(all.back().predictedTraceMs / 4.0), nullptr, BenefitAblation::None, r);
    // A partial item (checked against the CPU above) only where rates are chosen per item.
    if (r != ItemRate::Auto) {
      EXPECT_EQ(std::count_if(frames.begin(), frames.end(), [](const FrameTiming& f) { return f.partialShare > 0.0; }), 0);
    }
  }
}

// The shadow classifier (`classified`, shadows only) traces far fewer shadow rays than full
// RT, and its image stays far closer to full RT's than the shadow maps' is.
TEST(Items, TheShadowClassifierSavesRaysAndKeepsTheImage) {
  const Scene scene = loadScene(test::defaultScenePath());
  RenderSettings s = settingsFor(Policy::All, 320, 192);
  s.rayTracing.reflections = false;
  s.rayTracing.refractions = false;
  const test::ClassifierFrame c = test::classifierAgainstFullRt(scene, s, defaultCamera(scene, 320.0f / 192.0f));
  EXPECT_LT(c.rays, c.fullRays / 2) << "most shadow-map lookups are certain";
  EXPECT_GT(c.fallback, 0.0);
  EXPECT_LT(c.kept, 0.25 * c.fallback) << "classified " << c.kept << " against the shadow maps' " << c.fallback;
}

TEST(Items, BadClassifierSettingsAreRefusedNamingTheSetting) {
  const Scene scene = itemScene();
  for (float texels : {-1.0f, 65.0f, std::nanf("")}) {
    RenderSettings s = settingsFor(Policy::Benefit, 64, 64);
    s.rayTracing.shadowUncertaintyTexels = texels;
    test::expectRefusedNaming(scene, s, "shadowUncertaintyTexels");
  }
}

}  // namespace
}  // namespace raybudget
