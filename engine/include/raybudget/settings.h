// What raybudget renders with and reports: the policies, the settings, the passes and
// their timings, the cost model, the per-object metrics. Plain types, no Vulkan.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "raybudget/bvh_options.h"

namespace raybudget {

// Which objects get ray-traced effects: none, all (the full-RT reference), or, within
// RenderSettings::budgetMs, the paper's selection graph, density, or the nearest / random
// baselines (per object), or `benefit`: per item (an object's shadows, reflections,
// refractions) by the display error its tracing removes (docs/SELECTION.md). `classified`
// traces every item, shadows only where the shadow map is uncertain: what the classifier
// alone costs in error and saves in time.
enum class Policy { None, All, Paper, Density, Nearest, Random, Benefit, Classified };

// `benefit` with one of its parts left out, for the benchmark's ablations
// (docs/SELECTION.md): P in E = A·P·b (P = 1), the hysteresis S·I (I = 0), the measured b
// (b stays the prior), the shadow classifier (every pixel of a shadow item traces), the probe
// (probeShare 0: the selection gets the whole trace budget).
enum class BenefitAblation { None, NoCentrality, NoHysteresis, PriorOnly, NoClassifier, NoProbe };
// "", "no-centrality", "no-hysteresis", "prior-only", "no-classifier", "no-probe"
const char* ablationName(BenefitAblation ablation);
// Throws raybudget::Error naming the valid ones.
BenefitAblation parseAblation(const std::string& name);
const char* policyName(Policy policy);
// Throws raybudget::Error naming the policies.
Policy parsePolicy(const std::string& name);
bool isBudgeted(Policy policy);

// Which tracer the ray-traced effects use: our compute BVH, or the device's VK_KHR_ray_query
// with Vulkan acceleration structures (Renderer throws when the device has none).
enum class Tracer { Compute, Native };
const char* tracerName(Tracer tracer);

// The share of a selected item's pixels traced each frame: all, a checkerboard alternating
// each frame (1/2), one pixel of each 2x2 quad rotating each frame (1/4); the others are
// filled from traced neighbours on the same object, weighted by depth and normal. Auto:
// `benefit` chooses per item (the multiple-choice knapsack; the other policies trace at full).
enum class ItemRate { Full, Half, Quarter, Sixteenth, Auto };
const char* itemRateName(ItemRate rate);
ItemRate parseItemRate(const std::string& name);  // throws Error naming the choices

struct RayTracingSettings {
  bool shadows = true;       // any-hit rays per light instead of shadow maps
  bool reflections = true;   // mirror rays on surfaces with roughness <= maxRoughness
  bool refractions = true;   // rays through transmissive surfaces
  uint32_t depth = 1;        // reflection / refraction bounces, 1..4
  // Rougher surfaces keep the prefiltered environment for their reflections: a single
  // mirror ray would be noise on them (0..1).
  float maxRoughness = 0.35f;
  // `benefit` and `classified`: a pixel traces a light's shadow ray only where the shadow
  // map is uncertain: its PCF result strictly between lit and shadowed, or its depth tests
  // shadowUncertaintyTexels around the point disagree with the point's triangle plane there,
  // or that triangle meets the light edge-on or from behind (0: the PCF result alone; 0..64).
  // Off: every pixel of a selected shadow item traces.
  bool classifyShadows = true;
  float shadowUncertaintyTexels = 2.0f;
  // `benefit` and `classified`: a shadow ray ends a few texels past the nearest blocker the
  // light's shadow map holds around the point instead of at the light (off: at the light).
  bool shortenShadowRays = true;
  // `benefit`, `all` and `classified`: the rate every selected item is traced at (Auto:
  // `benefit` chooses one per item).
  ItemRate rate = ItemRate::Full;
  // With reduced rates: a reflection or refraction pixel not traced this frame adds to its
  // fallback what tracing changed there when it was last traced (reprojected, while the
  // object, its distance and, within a pixel's angle, the view direction there still match, and
  // younger than the rate's period), and a shadow pixel corrects its shadow maps by their error
  // where its point was last traced (while that point shows within half a pixel), before the
  // spatial fill from traced neighbours. The fills' histories (64 bytes a pixel for reflections
  // and refractions, 32 for shadows) are made when the renderer is made with a reduced `rate`;
  // without them restartSelection refuses a reduced rate for a scene that needs them.
  bool temporalFill = true;
  Tracer tracer = Tracer::Compute;
  SpatialSplits spatialSplits = SpatialSplits::Auto;  // the compute tracer's BVH build
};

struct RenderSettings;
// Throws raybudget::Error naming the setting out of its range.
void validateSettings(const RenderSettings& settings);

struct RenderSettings {
  uint32_t width = 1280;
  uint32_t height = 720;
  std::string device;              // substring of the Vulkan device name; empty: best available
  bool validation = false;         // Khronos validation + synchronization validation
  uint32_t shadowMapSize = 1024;   // directional/spot layers; point-light cube faces get half
  // A shadow-map lookup's point moves this many of the map's texels (their world size there)
  // along the surface's normal, against acne (with the shadow pass's slope-scaled bias).
  float shadowNormalOffset = 1.5f;
  // The shadow pass's slope-scaled depth bias: a caster's depth moves back this many times its
  // depth slope per texel. Above 2, shadow rays run to the light (shortenShadowRays ends them
  // past the map's nearest blocker, which covers two texels' slope).
  float shadowSlopeBias = 1.75f;
  // Each spot and point light's map takes the power-of-two size its reach covers on screen
  // (at most shadowMapSize; a shadow texel about a pixel there), rendered again when that
  // changes; off: every map at full size.
  bool shadowMapsFitScreen = true;
  // Glass shows the opaque frame lit behind it (Pass::BehindGlass); off: the environment alone.
  bool screenSpaceTransmission = true;
  // Reflections and what glass shows off screen come from reflection probes captured from
  // the scene (Pass::ReflectionProbes); off: the sky alone.
  bool reflectionProbes = true;
  // Smooth surfaces reflect what is on screen first (Pass::ScreenSpaceReflections, from the
  // previous frame's image); off: the probes and the sky alone.
  bool screenSpaceReflections = true;
  float exposure = 1.0f;
  float skyIntensity = 0.3f;       // sky radiance scale (ambient, reflections, background)
  std::string environmentMap;      // equirectangular OpenEXR replacing the procedural sky
  Policy policy = Policy::None;
  // The ray-tracing stage's time budget T, budgeted policies only: coverage + select + the
  // trace passes. The selection gets T less the coverage and select passes' learned time.
  float budgetMs = 4.0f;
  uint32_t graphPointers = 4;      // `paper`: N
  uint32_t seed = 1;               // `random`
  BenefitAblation benefitAblation = BenefitAblation::None;
  // `benefit`: the share of the trace budget (T less the stage's fixed cost) kept for the
  // sparse probe, which traces and measures left-out items on a rotating few tiles so that
  // their learned benefit stays fresh, without showing the result (0: no probe; 0..0.5).
  float probeShare = 0.05f;
  // Budgeted policies, with learnTimeScale: the share of frames the stage should hold T in if
  // the recent frames' prediction errors recur. The selection's budget is divided by that
  // quantile of their measured over predicted trace time (cost_model.h's headroom): higher
  // holds T more often and uses less of it (0.5..0.99; 0.5: the median error, about none).
  float budgetConfidence = 0.9f;
  // Budgeted policies, with learnTimeScale: the trace passes stop tracing once the stage has run
  // for about T on the device's clock, less the recent time of the fill after them, and the
  // pixels left keep their fallbacks (FrameTiming::deadlineCutPixels); the fill stops at about T
  // itself (FrameTiming::fillCutPixels). The selection's prediction decides what is traced, the
  // deadline bounds the stage where the prediction was wrong (docs/SELECTION.md, "The deadline").
  bool stageDeadline = true;
  // On a still view (the camera and every object where they were the frame before) the
  // coverage pass keeps the frame before's counts and only computes the objects' metrics
  // again: the same selection inputs for less of the stage's fixed cost (FrameTiming::coverageReused).
  bool reuseStillCoverage = true;
  // Learn the cost model's time scale and the stage's overhead (coverage + select) from the
  // timestamps (off: the prior stays, so a run selects the same objects on any machine;
  // per-object work per pixel is learned from the deterministic work counters either way).
  bool learnTimeScale = true;
  // Benchmarks: read each frame's candidates back and compute the 0/1-knapsack bound on the
  // value any selection within T could reach (FrameTiming::optimalValueBound).
  bool optimalBound = false;
  RayTracingSettings rayTracing;
  // Run the heuristic's per-object pass every frame (coverage, then A, P, D, V, C, R on the
  // GPU), readable with Renderer::objectMetrics().
  bool objectMetrics = false;
};

// Passes in frame order. Each is bracketed by timestamps; a skipped pass has no time.
// The trace passes also fill what reduced ray rates did not trace (RayTracingSettings::rate).
enum class Pass : uint32_t {
  GBuffer,
  Coverage,
  Select,
  ShadowMaps,
  Environment,
  TraceShadows,
  Lighting,  // direct light, and the raster fallback for reflections and refractions
  TraceEffects,
  Compose,
  BehindGlass,  // the opaque frame lit and mip-mapped for glass to show, then the transmissive draws
  ReflectionProbes,  // cube maps captured from the scene for the reflection fallback
  ScreenSpaceReflections,  // the depth pyramid and each smooth surface's mirror ray marched through it
  FillEffects,  // reflections and refractions where a reduced ray rate skipped the pixel, from traced neighbours
  Count
};
inline constexpr size_t kPassCount = size_t(Pass::Count);
const char* passName(Pass pass);

// Why a pass was left out of a frame (None: it ran). A pass the scene can never need is
// left out of every frame, and its pipelines are never built (Renderer::builtPipelines).
enum class PassSkip : uint8_t {
  None,
  PolicyTracesNothing,             // coverage, select, trace: policy none
  NoEffectInScene,                 // coverage, select: no switched-on effect the scene can show
  EffectsOff,                      // a trace pass: its effects switched off (RayTracingSettings)
  NoLights,                        // shadow maps, trace shadows: no light (with a shadow map)
  NoSmoothOrTransmissiveMaterial,  // trace effects: nothing to reflect or refract (SceneEffects)
  EveryPixelTracesShadows,         // shadow maps under `all`
  EnvironmentReady,                // the static environment after the first frame
  HostGBuffer,                     // gbuffer: recordFrame reads the host's
  ShadowMapsCurrent,               // shadow maps: no light's casters moved since they were rendered
  NoTransmissionInView,            // behind glass: no transmissive surface in view
  EveryPixelTracesRefractions,     // behind glass: `all` at full rate traces every transmissive pixel
  FallbackOff,                     // behind glass, reflection probes: switched off in RenderSettings
  ProbesCurrent,                   // reflection probes: nothing inside their boxes moved since they were captured
  NoReflectionProbe,               // reflection probes: none authored, and no surroundings to capture (reflectionProbesOf)
  NoPreviousFrame,                 // screen-space reflections: the first frame has no earlier image to reflect
  EveryPixelTracesReflections,     // screen-space reflections: `all` at full rate traces every smooth pixel's reflection
  NoSmoothMaterial,                // screen-space reflections: no material smooth enough for them
  BudgetBelowFixedCost,            // coverage, select, trace: T at or below the stage's learned fixed cost
  FullRate,                        // fill effects: every item traced at full ray rate
  ComposedInLighting,              // compose: no reflection or refraction traced, the lighting pass composed the frame
};
const char* passSkipText(PassSkip skip);

struct FrameTiming {
  uint64_t frame = 0;
  double tlasRebuildMs = 0.0;  // CPU time rebuilding the TLAS for moved objects (0: static)
  uint32_t tracedTiles = 0;    // 8x8 tiles the trace passes ran over (0: none selected or nothing traced)
  uint32_t shadowTiles = 0;    // of those, the shadow pass's: tiles showing a traced shadow item
  uint32_t effectTiles = 0;    // and the reflection and refraction pass's
  // The chunks of 4 pixels of those tiles each pass ran (16 a tile at full rate, 8 at 1/2, 4 at
  // 1/4, 1 at 1/16: the highest rate among the tile's items), and the fill of reflections and
  // refractions (one a tile where a reduced rate skips pixels: its invocation per 4x4 block).
  uint32_t shadowChunks = 0, effectChunks = 0, fillChunks = 0;
  uint32_t raysTraced = 0;     // ray queries the trace passes ran (shadow, reflection, refraction)
  // Pixels the stage's deadline (RenderSettings::stageDeadline) left to their fallbacks: per
  // trace pass, those it would have traced (or probed) after the deadline passed
  uint32_t deadlineCutPixels = 0;
  // Pixels a reduced rate skipped that the fill of reflections and refractions left to their
  // fallbacks past its own deadline, at about T (the stage would else have ended past T)
  uint32_t fillCutPixels = 0;
  uint32_t shadowMapViews = 0;  // shadow-map layers and cube faces rendered (0: every map was current)
  uint32_t shadowMapDraws = 0;  // draw calls into them (the casters inside each view)
  uint32_t shadowMapTexels = 0; // texels of the rendered views (each map's side from its screen coverage)
  uint32_t probesCaptured = 0;  // reflection probes captured (0: every probe was current)
  // Budgeted policies: the stage budget T, the part of it the selection got for the
  // candidates' work (T less the stage's learned fixed cost: coverage, select, the trace
  // passes' own; divided by the headroom of RenderSettings::budgetConfidence), the cost model's prediction for the trace passes (their fixed cost plus
  // the selection's work) and their measured time, objects selected and their summed R.
  double budgetMs = 0.0;
  double traceBudgetMs = 0.0;
  bool budgetBelowFixedCost = false;  // T at or below the stage's fixed cost: nothing traced
  double predictedTraceMs = 0.0;
  double measuredTraceMs = 0.0;
  uint32_t selectedObjects = 0;
  uint32_t selectionChanges = 0;  // objects selected or dropped since the previous frame
  // `benefit`: items whose option (left out, or traced at a rate) changed since the previous frame
  uint32_t itemOptionChanges = 0;
  // `benefit` with rates chosen per item: the share of its tiles the partial item (the first
  // left out, its cheapest rate on what the budget left) is traced on; 0: none
  double partialShare = 0.0;
  // The frames before this one in a row with its camera and objects (0 after any change): on a
  // still view the temporal fill carries what a reduced rate traced, and `benefit` with rates
  // chosen per item values the rates for it (docs/SELECTION.md).
  uint32_t stillFrames = 0;
  // The coverage pass kept the frame before's counts (RenderSettings::reuseStillCoverage)
  bool coverageReused = false;
  // false when every candidate fit the budget for certain (their summed cost at most 31/32
  // of T), so the select pass skipped the sort and selected them all
  bool selectionSorted = false;
  double optimalValueBound = 0.0;  // with RenderSettings::optimalBound: the knapsack bound on the value
  double cheapestCandidateMs = 0.0;  // with RenderSettings::optimalBound: the least predicted cost of a candidate (0: none)
  double candidatesMs = 0.0;         // with RenderSettings::optimalBound: the candidates' summed predicted cost
  double selectedValue = 0.0;
  // With testing::Checks::selectionAgainstCpu (raybudget/testing.h): whether the GPU selected
  // exactly the objects the CPU reference selects from the frame's candidates.
  std::optional<bool> selectionMatchesCpu;
  // With testing::Checks::selectionAgainstCpu: whether the GPU's per-object cost model (each
  // object's learned work per pixel, each candidate's predicted cost) equals its CPU
  // reference (engine/src/select/cost_model.h) bit for bit.
  std::optional<bool> costsMatchCpu;
  std::array<std::optional<double>, kPassCount> passMs{};  // GPU milliseconds
  std::array<PassSkip, kPassCount> skipped{};               // why each pass without a time was left out
  double ms(Pass p) const { return passMs[size_t(p)].value_or(0.0); }  // 0 where the pass did not run
  double totalMs() const;
  double traceMs() const;    // the trace passes (shadows, effects) and the fill of reflections and refractions at reduced rates
  double rtStageMs() const;  // the ray-tracing stage T bounds: coverage + select + trace
};

// What the cost model has learned: the stage's time is affine in the selection's work,
// coverage + select + trace fixed cost + ms per unit x work. Trace milliseconds per unit of
// predicted work (our work units for density, nearest and random; the paper's C for paper;
// benefit's item work units, its items' clock ticks (RB_WORK_PER_CLOCK_UNIT), which weigh
// shading and divergence as object work does not: a scale of one
// unit predicted another's items 5-10x too cheap), the coverage and select passes' time and
// the trace passes' fixed cost (dispatch, tile setup), which the selection subtracts from T.
// 0 = not learned (the prior; no fixed cost).
struct CostModel {
  double msPerWorkUnit = 0.0;
  double msPerPaperCost = 0.0;
  double msPerItemWorkUnit = 0.0;
  double stageOverheadMs = 0.0;
  double traceFixedMs = 0.0;
  // Trace time per ray counted, what an object not traced yet is priced at; and per ray an
  // item's prior counts (a shadow ray per light, a path with its hit's), what an item is.
  double msPerRay = 0.0;
  double msPerItemRay = 0.0;
  bool operator==(const CostModel&) const = default;
};
// The time scale the selection uses before it has measured any: ms per unit of predicted
// work at this render size (CostModel::msPerWorkUnit's prior, which its 0 stands for).
double priorMsPerWorkUnit(uint32_t width, uint32_t height);

// The paper's per-object quantities as the GPU computed them (engine/src/select/metrics.h
// is the CPU reference).
struct ObjectMetrics {
  uint32_t pixels = 0;
  // Of those, the pixels the classifier marked as needing reflection rays (roughness at or
  // below RayTracingSettings::maxRoughness) and refraction rays (transmissive); unlit none.
  // Counted in frames rendered with RenderSettings::objectMetrics only.
  uint32_t reflectionPixels = 0, refractionPixels = 0;
  float A = 0.0f, P = 0.0f, D = 0.0f, V = 0.0f, C = 0.0f, R = 0.0f;
  bool candidate = false;
  bool selected = false;  // ray-traced effects this frame (the select pass's choice)
  // Items (shadows, reflections, refractions: the RB_RT_* bits): those traced this frame;
  // with `benefit` or `classified`, the display error the trace passes measured per item
  // (summed over its traced pixels, each the mean absolute difference of the tonemapped
  // sRGB channels against the fallback) and its traversal work, counted since the last
  // select pass; and with `benefit` each item's learned benefit per covered pixel.
  uint32_t selectedItems = 0;
  std::array<ItemRate, 3> itemRate{};  // the rate each selected item is traced at (Full when not selected)
  std::array<float, 3> itemError{};
  std::array<uint32_t, 3> itemWork{};
  std::array<uint64_t, 3> itemTicks{};  // subgroup clock ticks the trace passes spent on the item
  std::array<float, 3> itemBenefit{};
  std::array<float, 3> itemCostPerPixel{};  // `benefit`: the learned cost per traced pixel, work units (0: not learned)
  std::array<float, 3> itemFillPerPixel{};  // `benefit`: the learned cost per pixel a reduced rate skipped (0: not learned)
  // This frame's counts behind the learned costs (`benefit` and `classified`): the pixels its
  // trace passes traced for the item (`itemTicks` over them is its cost per traced pixel at its
  // rate), and of the pixels its reduced rate skipped, those in the fill's timed workgroups
  // (one in four) and their ticks.
  std::array<uint32_t, 3> itemTracedPixels{}, itemSkippedPixels{};
  std::array<uint64_t, 3> itemSkippedTicks{};
  // The share of its 8x8 tiles a selected item is traced on: 1, or below for `benefit`'s
  // partial item (with rates chosen per item: the budget the knapsack left, docs/SELECTION.md)
  std::array<float, 3> itemTileShare{1.0f, 1.0f, 1.0f};
  // Of the reflection and refraction pixels (the counts above), those in a 2x2 quad where two pixels of
  // the object have normals further apart than RB_FILL_DETAIL_COS: where a reduced rate's
  // spatial fill keeps little (docs/SELECTION.md, "Ray rates").
  uint32_t detailedPixels = 0;
};

// The ray tracer's acceleration structure, built once when the Renderer is made.
struct AccelStats {
  double buildMs = 0.0;     // compute tracer: BLAS + TLAS on the CPU; native: on the device
  size_t triangles = 0;     // in the per-mesh structures (compute tracer: a shared one once)
  size_t references = 0;    // leaf entries: compute tracer, triangles plus spatial-split pieces
  size_t splitMeshes = 0;   // meshes built with spatial splits (compute tracer)
  size_t sharedMeshes = 0;  // meshes using another's structure, same triangles (compute tracer)
  size_t bytes = 0;         // device memory
};

}  // namespace raybudget
