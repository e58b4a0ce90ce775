#include "cli_options.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cmath>
#include <optional>

#include "raybudget/error.h"

namespace raybudget::cli {

const char* kUsage = R"(raybudget: ray-traced effects under a time budget for a deferred renderer

usage:
  raybudget render SCENE.gltf|SCENE.glb [options]   render frames, write images and stats
  raybudget sweep SCENE.gltf|SCENE.glb [options]    run time against error over policies and
                                                    budgets (raybudget sweep --help)
  raybudget soak SCENE.gltf|SCENE.glb [options]     a long run with T as a square wave and a CPU
                                                    load: memory, NaN and adherence
                                                    (raybudget soak --help)
  raybudget check SCENE.gltf|SCENE.glb [--strict]   load only: what the loader repairs, or why it
                                                    refuses the file (docs/ROBUSTNESS.md)
  raybudget devices                                 list the Vulkan devices
  raybudget --help

render options:
  --frames N            frames to render (default 1)
  --width W --height H  image size (default 1280x720)
  --out DIR             output folder (default ./out): frame.png, frame.exr, stats.csv
  --camera static|orbit|flythrough
                        the scene's camera (or one framing the scene), a full orbit
                        around its target, or a fly-through over the target to the far
                        side, over the N frames (default static)
  --device NAME         use the Vulkan device whose name contains NAME
  --validation          enable VK_LAYER_KHRONOS_validation (fails on any message)
  --exposure E          linear exposure before tonemapping (default 1)
  --sky S               sky radiance scale (default 0.3)
  --env FILE.exr        equirectangular HDR environment instead of the procedural sky
  --policy P            which objects get ray-traced shadows, reflections and refractions:
                        none (all raster fallbacks, the default), all (the full-RT
                        reference), or within --budget-ms: paper (the paper's selection
                        graph), density (relevance per predicted cost), nearest, random
                        (per object), or benefit (per item: an object's shadows,
                        reflections, refractions, by the display error its tracing removes
                        per predicted cost); classified traces every item, shadows only
                        where the shadow map is uncertain
  --budget-ms T         the ray-tracing stage's time budget in milliseconds: coverage,
                        select and the trace passes (default 4)
  --seed S              the random policy's seed (default 1)
  --graph-pointers N    the paper's higher-relevance pointers per node, 0..64 (default 4)
  --optimal-bound       write each frame's 0/1-knapsack bound on the selectable value
                        (optimal_value_bound in stats.csv; CPU work, for benchmarks)
  --depth D             reflection/refraction bounces, 1..4 (default 1)
  --max-roughness R     reflections are traced on surfaces up to this roughness, 0..1;
                        rougher ones keep the prefiltered environment (default 0.35)
  --shadow-uncertainty X
                        benefit and classified: shadow rays only where the shadow map is
                        uncertain, its PCF result between lit and shadowed, its depth tests
                        X texels around disagreeing with the surface's plane there, or the
                        surface meeting the light edge-on, 0..64 (default 2; 0: PCF alone)
  --no-shadow-classifier
                        benefit and classified: every pixel of a traced shadow item traces
  --full-shadow-rays    benefit and classified: shadow rays run to the light, not ending just
                        past the nearest blocker the shadow map holds around the point
  --rate full|half|quarter|sixteenth|auto
                        benefit, all and classified: trace every selected item on all its
                        pixels, a checkerboard, one pixel per 2x2 quad or per 4x4 block each
                        frame, and fill the others from traced neighbours on the same object
                        (default full); auto: benefit chooses a rate per item (at the priors
                        1/16, 1/4 or full for reflections and refractions, 1/4 or full for
                        shadows)
  --no-temporal-fill    with reduced rates, fill the pixels not traced this frame from traced
                        neighbours alone (default: first from what tracing changed there when
                        last traced, reprojected, while its object and distance and, for
                        reflections and refractions, the view direction still match, until
                        the rate traces it again)
  --explain[=frames]    print the pass plan: per pass the frames it ran in and its median
                        time, the frames it was left out of and why; the effects the scene can
                        show, the pipelines built, the pixels per effect that could take rays
                        and those traced, whether the view was still; =frames also prints each frame's selected items
                        (adds the per-object metrics pass to coverage)
  --item-stats          write items.csv: per object and effect (item) in the last frame, its
                        pixels, whether traced, and with benefit or classified the display
                        error its tracing removed, its clock ticks and traversal work, the
                        pixels traced and those its rate skipped with their fill's ticks,
                        and with benefit its learned benefit, cost per traced pixel and
                        cost per pixel a reduced rate skips, and its share of tiles; with
                        --explain=frames also items-N.csv for each frame N
  --budget-confidence C
                        the share of frames the stage should hold T in if recent prediction
                        errors recur: the selection's budget is divided by that quantile of
                        measured over predicted trace time, 0.5..0.99 (default 0.9)
  --no-stage-deadline   budgeted policies: the trace passes trace all that was selected even
                        past T (default: they stop once the stage has run for T on the
                        device's clock and leave the pixels left to their fallbacks)
  --no-coverage-reuse   count every frame's coverage (default: on a still view the coverage
                        pass keeps the frame before's counts, coverage_reused in stats.csv)
  --probe-share F       benefit: the share of the trace budget for the sparse probe, which
                        traces left-out items on a few rotating tiles to measure their
                        benefit, not shown; 0..0.5 (default 0.05; 0: no probe)
  --benefit-ablation A  benefit with a part left out: no-centrality (P = 1), no-hysteresis
                        (I = 0), prior-only (b never measured), no-classifier, no-probe
  --tracer compute|native
                        compute: our BVH in compute shaders (default); native: the device's
                        VK_KHR_ray_query with Vulkan acceleration structures
  --bvh-splits auto|always|never
                        spatial splits in the compute tracer's BVH build: auto (default)
                        splits meshes whose triangles differ much in size
  --no-rt-shadows, --no-rt-reflections, --no-rt-refractions
                        keep that effect on its raster fallback even where traced
  --shadow-map-size S   shadow map resolution (default 1024; point-light cubes get S/2)
  --shadow-normal-offset X
                        a shadow-map lookup moves X of the map's texels along the surface
                        normal, against acne, 0..16 (default 1.5)
  --shadow-slope-bias X the shadow pass moves a caster's depth back X times its depth slope
                        per texel, against acne, 0..16 (default 1.75)
  --full-size-shadow-maps
                        every shadow map at --shadow-map-size (default: spot and point
                        lights' maps sized from the screen coverage of their reach)
  --no-screen-space-transmission
                        glass falls back to the environment alone, not the opaque frame lit
                        behind it
  --no-reflection-probes
                        reflections fall back to the sky alone, not probes captured from the
                        scene
  --no-screen-space-reflections
                        smooth surfaces do not reflect what is on screen (the probes and the
                        sky alone)
  --strict              refuse a scene the loader would repair (NaN normals, unreadable
                        images, zero-area triangles...; docs/ROBUSTNESS.md)
)";

uint32_t parseUint(const std::string& option, const std::string& value, uint32_t lo, uint32_t hi) {
  uint32_t v = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (ec != std::errc() || end != value.data() + value.size() || v < lo || v > hi)
    throw Error(option + " needs a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got '" + value + "'");
  return v;
}

// The whole of `value` as a finite float, or nothing.
std::optional<float> parseFinite(const std::string& value) {
  size_t used = 0;
  float v = 0.0f;
  try {
    v = std::stof(value, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != value.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// A number within lo..hi (inclusive); the error names the option.
// A range bound as a user writes it: 0.0, 64.0, 0.99.
std::string boundText(float v) {
  char text[32];
  std::snprintf(text, sizeof text, v == std::floor(v) ? "%.1f" : "%g", double(v));
  return text;
}

float parseWithin(const std::string& option, const std::string& value, float lo, float hi) {
  const std::optional<float> v = parseFinite(value);
  if (!v || *v < lo || *v > hi)
    throw Error(option + " needs a number within " + boundText(lo) + ".." + boundText(hi) + ", got '" + value + "'");
  return *v;
}

float parsePositive(const std::string& option, const std::string& value) {
  const std::optional<float> v = parseFinite(value);
  if (!v || *v <= 0.0f) throw Error(option + " needs a positive number, got '" + value + "'");
  return *v;
}

const std::string& optionValue(const std::vector<std::string>& args, size_t& i) {
  if (i + 1 >= args.size()) throw Error(args[i] + " needs a value");
  return args[++i];
}

bool RenderTarget::parse(const std::vector<std::string>& args, size_t& i) {
  const std::string& a = args[i];
  if (a == "--width") width = parseUint(a, optionValue(args, i), 16, 16384);
  else if (a == "--height") height = parseUint(a, optionValue(args, i), 16, 16384);
  else if (a == "--device") device = optionValue(args, i);
  else if (a == "--validation") validation = true;
  else return false;
  return true;
}

RenderSettings RenderTarget::settings() const {
  RenderSettings s;
  applyTo(s);
  return s;
}

void RenderTarget::applyTo(RenderSettings& s) const {
  s.width = width;
  s.height = height;
  s.device = device;
  s.validation = validation;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

void sceneArgument(const std::string& arg, std::string& scene, const std::string& hint) {
  if (!arg.empty() && arg[0] == '-') throw Error("unknown option " + arg + hint);
  if (!scene.empty()) throw Error("more than one scene given: '" + scene + "' and '" + arg + "'");
  scene = arg;
}

Camera cameraOnPath(const std::string& path, const Camera& start, uint32_t frame, uint32_t frameCount, FlythroughShape shape) {
  if (path == "orbit") return orbitCamera(start, frame, frameCount);
  if (path == "flythrough") return flythroughCamera(start, frame, frameCount, shape);
  return start;
}

Camera cameraApproaching(const std::string& path, const Camera& start, uint32_t frame, uint32_t frameCount, uint32_t stepsBack,
                         FlythroughShape shape) {
  constexpr int64_t kSteps = 100;  // steps per frame spacing
  // The orbit's frames divide a turn (frame / count), the fly-through's its length from end to
  // end (frame / (count - 1)): the same path at kSteps times the frames keeps its frames.
  const bool wraps = path == "orbit";
  const int64_t fine = wraps ? kSteps * frameCount : kSteps * (int64_t(frameCount) - 1) + 1;
  int64_t at = kSteps * int64_t(frame) - int64_t(stepsBack);
  at = wraps ? ((at % fine) + fine) % fine : std::max<int64_t>(at, 0);
  return cameraOnPath(path, start, uint32_t(at), uint32_t(std::max<int64_t>(fine, 1)), shape);
}

bool parseImageOption(const std::vector<std::string>& args, size_t& i, RenderSettings& s) {
  const std::string& a = args[i];
  if (a == "--no-screen-space-transmission") s.screenSpaceTransmission = false;
  else if (a == "--no-reflection-probes") s.reflectionProbes = false;
  else if (a == "--no-screen-space-reflections") s.screenSpaceReflections = false;
  else if (a == "--no-temporal-fill") s.rayTracing.temporalFill = false;
  else if (a == "--shadow-normal-offset") s.shadowNormalOffset = parseWithin(a, optionValue(args, i), 0.0f, 16.0f);
  else if (a == "--shadow-slope-bias") s.shadowSlopeBias = parseWithin(a, optionValue(args, i), 0.0f, 16.0f);
  else if (a == "--budget-confidence") s.budgetConfidence = parseWithin(a, optionValue(args, i), 0.5f, 0.99f);
  else if (a == "--no-stage-deadline") s.stageDeadline = false;
  else if (a == "--no-coverage-reuse") s.reuseStillCoverage = false;
  else return false;
  return true;
}

RenderCommand parseRender(const std::vector<std::string>& args) {
  RenderCommand c;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& { return optionValue(args, i); };
    if (parseImageOption(args, i, c.settings)) continue;
    if (a == "--frames") c.frames = parseUint(a, value(), 1, 1000000);
    else if (a == "--width") c.settings.width = parseUint(a, value(), 1, 16384);
    else if (a == "--height") c.settings.height = parseUint(a, value(), 1, 16384);
    else if (a == "--out") c.out = value();
    else if (a == "--camera") {
      c.camera = value();
      if (c.camera != "static" && c.camera != "orbit" && c.camera != "flythrough")
        throw Error("--camera must be static, orbit or flythrough, got '" + c.camera + "'");
    } else if (a == "--device") c.settings.device = value();
    else if (a == "--validation") c.settings.validation = true;
    else if (a == "--exposure") c.settings.exposure = parsePositive(a, value());
    else if (a == "--sky") c.settings.skyIntensity = parsePositive(a, value());
    else if (a == "--env") c.settings.environmentMap = value();
    else if (a == "--policy") c.settings.policy = parsePolicy(value());
    else if (a == "--budget-ms") c.settings.budgetMs = parsePositive(a, value());
    else if (a == "--seed") c.settings.seed = parseUint(a, value(), 0, 0xFFFFFFFFu);
    else if (a == "--graph-pointers") c.settings.graphPointers = parseUint(a, value(), 0, 64);
    else if (a == "--optimal-bound") c.settings.optimalBound = true;
    else if (a == "--tracer") {
      const std::string t = value();
      if (t == "compute") c.settings.rayTracing.tracer = Tracer::Compute;
      else if (t == "native") c.settings.rayTracing.tracer = Tracer::Native;
      else throw Error("--tracer must be compute or native, got '" + t + "'");
    } else if (a == "--bvh-splits") {
      const std::string t = value();
      if (t == "auto") c.settings.rayTracing.spatialSplits = SpatialSplits::Auto;
      else if (t == "always") c.settings.rayTracing.spatialSplits = SpatialSplits::Always;
      else if (t == "never") c.settings.rayTracing.spatialSplits = SpatialSplits::Never;
      else throw Error("--bvh-splits must be auto, always or never, got '" + t + "'");
    } else if (a == "--depth") c.settings.rayTracing.depth = parseUint(a, value(), 1, 4);
    else if (a == "--max-roughness") c.settings.rayTracing.maxRoughness = parseWithin(a, value(), 0.0f, 1.0f);
    else if (a == "--shadow-uncertainty") c.settings.rayTracing.shadowUncertaintyTexels = parseWithin(a, value(), 0.0f, 64.0f);
    else if (a == "--item-stats") {
      c.itemStats = true;
      c.settings.objectMetrics = true;
    } else if (a == "--explain" || a == "--explain=frames") {
      c.explain = a == "--explain" ? RenderCommand::Explain::Plan : RenderCommand::Explain::Frames;
      c.settings.objectMetrics = true;  // the per-effect pixel counts and the selected items
    } else if (a.rfind("--explain=", 0) == 0) {
      throw Error("--explain takes no value or =frames, got '" + a + "'");
    } else if (a == "--no-shadow-classifier") c.settings.rayTracing.classifyShadows = false;
    else if (a == "--full-shadow-rays") c.settings.rayTracing.shortenShadowRays = false;
    else if (a == "--rate") c.settings.rayTracing.rate = parseItemRate(value());
    else if (a == "--benefit-ablation") c.settings.benefitAblation = parseAblation(value());
    else if (a == "--probe-share") c.settings.probeShare = parseWithin(a, value(), 0.0f, 0.5f);
    else if (a == "--no-rt-shadows") c.settings.rayTracing.shadows = false;
    else if (a == "--strict") c.load.strict = true;
    else if (a == "--no-rt-reflections") c.settings.rayTracing.reflections = false;
    else if (a == "--no-rt-refractions") c.settings.rayTracing.refractions = false;
    else if (a == "--shadow-map-size") c.settings.shadowMapSize = parseUint(a, value(), 16, 8192);
    else if (a == "--full-size-shadow-maps") c.settings.shadowMapsFitScreen = false;
    else sceneArgument(a, c.scene, " (see raybudget --help)");
  }
  if (c.scene.empty()) throw Error("render needs a scene file (see raybudget --help)");
  return c;
}

}  // namespace raybudget::cli
