// Per-pass timestamps: every executed pass reports a time, the static environment and the
// shadow maps of a static scene only on the first frame, and results arrive for every frame
// without the caller waiting on each.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <functional>

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
    for (Pass p : {Pass::GBuffer, Pass::Lighting}) {
      ASSERT_TRUE(t.passMs[size_t(p)].has_value()) << passName(p) << " frame " << i;
      EXPECT_GE(*t.passMs[size_t(p)], 0.0);
    }
    EXPECT_EQ(t.skipped[size_t(Pass::Compose)], PassSkip::ComposedInLighting) << "nothing traced: the lighting pass composes";
    EXPECT_FALSE(t.passMs[size_t(Pass::Compose)].has_value());
    EXPECT_EQ(t.passMs[size_t(Pass::Environment)].has_value(), i == 0) << "the static environment is built once";
    EXPECT_EQ(t.passMs[size_t(Pass::ShadowMaps)].has_value(), i == 0) << "the shadow maps of a static scene are rendered once";
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

// stillFrames counts the frames before each one with its camera and objects: it restarts at a
// camera move and at a moved object (whose history the temporal fill can no longer carry).
TEST(FrameTiming, StillFramesCountTheFramesSinceTheViewOrAnObjectLastChanged) {
  RenderSettings settings;
  settings.width = 64;
  settings.height = 64;
  settings.validation = true;
  const Scene scene = twoTriangles();
  Renderer renderer(scene, settings);
  const Camera cam = defaultCamera(scene, 1.0f);
  Camera moved = cam;
  moved.position.x += 1e-3f;
  std::vector<FrameTiming> timings;
  auto render = [&](const Camera& c) {
    for (const FrameTiming& t : renderer.render(c)) timings.push_back(t);
  };
  render(cam), render(cam), render(cam), render(moved), render(moved);
  renderer.setObjectTransform(0, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.1f, 0.0f)));
  render(moved), render(moved);
  for (const FrameTiming& t : renderer.finish()) timings.push_back(t);
  ASSERT_EQ(timings.size(), 7u);
  const uint32_t expected[] = {0, 1, 2, 0, 1, 0, 1};
  for (size_t i = 0; i < timings.size(); ++i) EXPECT_EQ(timings[i].stillFrames, expected[i]) << "frame " << i;
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

namespace raybudget {
namespace {

bool built(const Renderer& r, const std::string& pipeline) {
  const std::vector<std::string> p = r.builtPipelines();
  return std::find(p.begin(), p.end(), pipeline) != p.end();
}

// Any pipeline of the effects pass, whichever paths it holds.
bool builtEffects(const Renderer& r) {
  const std::vector<std::string> p = r.builtPipelines();
  return std::any_of(p.begin(), p.end(), [](const std::string& name) { return name.starts_with("trace_effects"); });
}

// Two frames of `scene` under `policy`; the renderer stays for its pipelines.
std::vector<FrameTiming> twoFrames(Renderer& r, const Scene& scene) { return test::renderStill(r, defaultCamera(scene, r.aspect()), 2); }

void expectLeftOut(const FrameTiming& t, Pass p, PassSkip why) {
  EXPECT_FALSE(t.passMs[size_t(p)].has_value()) << passName(p) << " has a time";
  EXPECT_EQ(t.skipped[size_t(p)], why) << passName(p) << ": " << passSkipText(t.skipped[size_t(p)]);
}

// The triangles' default material is rough and opaque: full RT traces their shadows and
// builds no reflection or refraction pipeline.
TEST(PassPlan, ARoughOpaqueSceneRunsNoEffectsPass) {
  const Scene scene = twoTriangles();
  Renderer r(scene, test::settingsFor(Policy::All, 96, 64));
  const SceneEffects e = r.sceneEffects();
  EXPECT_TRUE(e.shadows && !e.reflections && !e.refractions);
  for (const FrameTiming& t : twoFrames(r, scene)) {
    expectLeftOut(t, Pass::TraceEffects, PassSkip::NoSmoothOrTransmissiveMaterial);
    expectLeftOut(t, Pass::ShadowMaps, PassSkip::EveryPixelTracesShadows);
    EXPECT_TRUE(t.passMs[size_t(Pass::TraceShadows)].has_value());
  }
  EXPECT_TRUE(built(r, "trace_shadows"));
  EXPECT_FALSE(builtEffects(r));
  test::expectValidationClean(r.validationMessages());
}

TEST(PassPlan, ASceneWithoutLightsRunsNoShadowWork) {
  Scene scene = twoTriangles();
  scene.lights.clear();
  Renderer r(scene, test::settingsFor(Policy::All, 96, 64));
  for (const FrameTiming& t : twoFrames(r, scene)) {
    expectLeftOut(t, Pass::TraceShadows, PassSkip::NoLights);
    expectLeftOut(t, Pass::ShadowMaps, PassSkip::NoLights);
    expectLeftOut(t, Pass::Coverage, PassSkip::NoEffectInScene);
    expectLeftOut(t, Pass::Select, PassSkip::NoEffectInScene);
  }
  EXPECT_FALSE(built(r, "trace_shadows"));
  EXPECT_FALSE(built(r, "shadow_maps"));
  test::expectValidationClean(r.validationMessages());
}

TEST(PassPlan, PolicyNoneTracesNothingAndBuildsNoTracePipeline) {
  const Scene scene = loadScene(test::defaultScenePath());
  Renderer r(scene, test::settingsFor(Policy::None, 96, 64));
  const SceneEffects e = r.sceneEffects();
  EXPECT_TRUE(e.shadows && e.reflections && e.refractions) << "the court has mirrors and glass";
  const std::vector<FrameTiming> frames = twoFrames(r, scene);
  ASSERT_EQ(frames.size(), 2u);
  for (const FrameTiming& t : frames) {
    for (Pass p : {Pass::Coverage, Pass::Select, Pass::TraceShadows, Pass::TraceEffects}) expectLeftOut(t, p, PassSkip::PolicyTracesNothing);
  }
  EXPECT_TRUE(frames[0].passMs[size_t(Pass::ShadowMaps)].has_value());
  expectLeftOut(frames[1], Pass::ShadowMaps, PassSkip::ShadowMapsCurrent);
  expectLeftOut(frames[1], Pass::Environment, PassSkip::EnvironmentReady);
  EXPECT_FALSE(built(r, "trace_shadows") || builtEffects(r));
  // Switching the effects off leaves their pass out for that reason.
  RenderSettings off = test::settingsFor(Policy::All, 96, 64);
  off.rayTracing.reflections = off.rayTracing.refractions = false;
  Renderer noEffects(scene, off);
  for (const FrameTiming& t : twoFrames(noEffects, scene)) expectLeftOut(t, Pass::TraceEffects, PassSkip::EffectsOff);
  EXPECT_FALSE(builtEffects(noEffects));
  test::expectValidationClean(r.validationMessages());
  test::expectValidationClean(noEffects.validationMessages());
}

// The triangles with one material for all: `m`.
Scene twoTrianglesOf(const Material& m) {
  Scene scene = twoTriangles();
  scene.materials = {m};
  for (Mesh& mesh : scene.meshes)
    for (Primitive& p : mesh.primitives) p.material = 0;
  return scene;
}

// The effects pass's pipelines hold only the paths the scene can show and the settings switch
// on; the others' code is compiled out (RB_PATHS_CONSTANT_ID).
TEST(PassPlan, TheEffectsPipelineHoldsOnlyThePathsTheSceneShows) {
  Material mirror;
  mirror.metallic = 1.0f;
  mirror.roughness = 0.05f;
  Material glass;
  glass.metallic = 0.0f;
  glass.roughness = 0.6f;  // too rough to trace its reflection
  glass.transmission = 1.0f;
  struct Case {
    Scene scene;
    bool refractionsOn;
    std::string pipeline;
  };
  const Scene court = loadScene(test::defaultScenePath());
  for (const Case& c : {Case{twoTrianglesOf(mirror), true, "trace_effects(reflections)"}, Case{twoTrianglesOf(glass), true, "trace_effects(refractions)"},
                        Case{court, true, "trace_effects(reflections,refractions)"}, Case{court, false, "trace_effects(reflections)"}}) {
    RenderSettings s = test::settingsFor(Policy::All, 96, 64);
    s.rayTracing.refractions = c.refractionsOn;
    Renderer r(c.scene, s);
    for (const FrameTiming& t : twoFrames(r, c.scene)) EXPECT_TRUE(t.passMs[size_t(Pass::TraceEffects)].has_value()) << c.pipeline;
    const std::vector<std::string> p = r.builtPipelines();
    EXPECT_EQ(std::count_if(p.begin(), p.end(), [](const std::string& name) { return name.starts_with("trace_effects"); }), 1) << c.pipeline;
    EXPECT_TRUE(built(r, c.pipeline)) << c.pipeline;
    test::expectValidationClean(r.validationMessages());
  }
}

// A fallback the scene or its settings cannot use keeps no full-size image: the device memory a
// renderer holds drops by at least that image's size when it is switched off or has nothing to
// show (screen-space transmission's half-resolution copy, screen-space reflections' image and
// depth pyramid, the shadow maps, the G-buffer's layers target).
TEST(PassPlan, AFallbackTheSceneCannotUseHoldsNoFullSizeImage) {
  constexpr int64_t kW = 640, kH = 360;
  auto heldBytes = [&](const Scene& scene, const std::function<void(RenderSettings&)>& change) {
    RenderSettings s = test::settingsFor(Policy::None, uint32_t(kW), uint32_t(kH));
    change(s);
    return int64_t(Renderer(scene, s).allocatedBytes());
  };
  auto same = [](RenderSettings&) {};
  Material mirror;
  mirror.roughness = 0.05f;
  Material glass;
  glass.metallic = 0.0f;
  glass.roughness = 0.6f;
  glass.transmission = 1.0f;
  const Scene mirrors = twoTrianglesOf(mirror), glassy = twoTrianglesOf(glass);
  const int64_t glassOn = heldBytes(glassy, same), glassOff = heldBytes(glassy, [](RenderSettings& s) { s.screenSpaceTransmission = false; });
  EXPECT_GE(glassOn - glassOff, kW / 2 * kH / 2 * 8) << "the behind-glass copy (RGBA16F, half size)";
  const int64_t ssrOn = heldBytes(mirrors, same), ssrOff = heldBytes(mirrors, [](RenderSettings& s) { s.screenSpaceReflections = false; });
  const int64_t ssrBytes = kW * kH * 8 + kW / 2 * kH / 2 * 4;
  EXPECT_GE(ssrOn - ssrOff, ssrBytes) << "the reflections' image (RGBA16F) and depth pyramid from half size (R32F)";
  const int64_t rough = heldBytes(twoTriangles(), same);
  EXPECT_GE(ssrOn - rough, ssrBytes) << "a scene with nothing smooth has no reflection images";
  Material coated;
  coated.clearcoat = 1.0f;
  EXPECT_GE(heldBytes(twoTrianglesOf(coated), same) - rough, kW * kH * 16 - 4096) << "a scene without layered materials draws no layers target (a 1x1 stands in)";
  EXPECT_GE(glassOn - rough, kW / 2 * kH / 2 * 8) << "a scene without glass has no behind-glass copy";
  Material unlitGlass = glass;
  unlitGlass.unlit = true;  // traces nothing, but is drawn over the opaque frame behind it like any glass
  EXPECT_GE(heldBytes(twoTrianglesOf(unlitGlass), same) - rough, kW / 2 * kH / 2 * 8) << "unlit glass keeps the behind-glass copy";
  Scene unlit = twoTriangles();
  unlit.lights.clear();
  const int64_t mapBytes = int64_t(RenderSettings{}.shadowMapSize) * RenderSettings{}.shadowMapSize * 4;
  EXPECT_GE(rough - heldBytes(unlit, same), mapBytes - 4096) << "the sun's shadow map (a 1x1 stands in)";
}

}  // namespace
}  // namespace raybudget
