// The core: a frame's coverage, select, raster fallbacks, trace passes, lighting and
// compose (and, for hosts without one, the G-buffer raster) recorded into a host's command
// buffer on the host's device, two frame slots in turn, every pass bracketed by timestamps.
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>

#include "behind_glass_comp.h"
#include "compose_comp.h"
#include "fill_effects_comp.h"
#include "lighting_comp.h"
#include "passes/descriptors.h"
#include "passes/environment.h"
#include "passes/frame_targets.h"
#include "passes/gbuffer.h"
#include "passes/reflection_probes.h"
#include "passes/scene_gpu.h"
#include "passes/screen_pass.h"
#include "passes/screen_reflections.h"
#include "passes/shadow_maps.h"
#include "passes/tile_list_pass.h"
#include "raybudget/core.h"
#include "raybudget/error.h"
#include "raybudget/testing.h"
#include "select/object_params.h"
#include "select/selection_stage.h"
#include "shared/config.h"
#include "shared/types.h"
#include "vk/check.h"
#include "vk/context.h"
#include "vk/timestamps.h"

namespace raybudget::core {
namespace {

constexpr uint32_t kFramesInFlight = 2;

// Whether reflections and refractions at `rate` need the fill's history (64 bytes a pixel):
// a reduced rate on a scene that shows either.
bool needsFillHistory(ItemRate rate, const SceneEffects& effects) { return rate != ItemRate::Full && (effects.reflections || effects.refractions); }

// Whether shadows at `rate` need the shadow fill's history (32 bytes a pixel): a reduced rate,
// ray-traced shadows and a light.
bool needsShadowHistory(ItemRate rate, const RayTracingSettings& rt, uint32_t lightCount) {
  return rate != ItemRate::Full && rt.shadows && lightCount > 0;
}

}  // namespace

struct Context::Impl {
  struct Slot {
    vk::Buffer uniforms;
    GBuffer gbuffer;        // the views the slot's sets read the G-buffer from
    bool recorded = false;  // recorded, its timings not yet collected
    uint64_t frame = 0;
    std::array<PassSkip, kPassCount> skipped{};  // why each pass not recorded was left out
    double tlasRebuildMs = 0.0;
    passes::ShadowMapPass::Recorded shadowMapsRecorded;
    uint32_t probesCaptured = 0;
    uint32_t stillFrames = 0;  // FrameTiming::stillFrames
    bool coverageReused = false;  // FrameTiming::coverageReused
    PassSkip ssr = PassSkip::NoPreviousFrame;  // None: smooth surfaces reflect what is on screen
    PassSkip behindGlass = PassSkip::NoTransmissionInView;  // None: glass shows the opaque frame lit behind it
    glm::uvec4 behindGlassRect{0};                          // the pixels lit for it
    vk::Buffer updateStaging;  // moved objects: new TLAS nodes, instances and object records
  };

  RenderSettings settings;
  uint32_t deadlineTicks = 0;      // testing::Checks::stageDeadlineTicks (0: the one learned from T)
  uint32_t fillDeadlineTicks = 0;  // testing::Checks::fillDeadlineTicks (0: the one at about T)
  bool stageSkipped = false;  // the frame being recorded leaves the ray-tracing stage out (SelectionStage::skipsStage)
  SceneEffects effects;  // what the scene can show at all: no pass, no pipeline for the rest
  bool ssrUseful;        // a material is smooth enough for screen-space reflections
  glm::vec3 sunDirection;
  vk::Context ctx;  // the host's device, borrowed
  passes::SceneGpu scene;
  passes::FrameTargets targets;
  passes::Samplers samplers;
  passes::PassLayouts layouts;  // each pass's descriptor set layout and per-slot sets
  vk::TimestampPool timestamps;
  // Coverage, select, the tile list and the cost model: the selection half of the stage.
  select::SelectionStage selection;
  passes::GBufferPass gbuffer;
  std::optional<passes::ShadowMapPass> shadowMaps;  // only when a light has a shadow map
  passes::EnvironmentPass environment;
  passes::ReflectionProbePass probes;
  passes::ScreenReflectionPass screenReflections;
  float ssrReach;      // their rays' length: the diagonal of the scene's bounds
  std::optional<glm::mat4> previousViewProj;  // the last recorded frame's (none before the first)
  glm::vec3 previousCamera{0.0f};             // its camera position
  passes::ScreenPass lighting;
  passes::ScreenPass compose;
  passes::ScreenPass behindGlassCopy;
  passes::TileListPass traceShadows;
  passes::TileListPass traceEffects;
  passes::TileListPass fillEffects;
  Slot slots[kFramesInFlight];
  uint64_t frameIndex = 0;
  bool environmentReady = false;
  bool tracedMaskWritten = true;  // the traced mask may hold marks (at first: undefined contents)
  bool objectsMoved = false;
  // The coverage buffers hold the last recorded frame's counts (CoveragePass::record's reuse),
  // counted with the classifier or without.
  bool coverageCounted = false, coverageClassified = false;
  static constexpr uint32_t kRecountStillCoverage = 8;
  uint32_t stillFrames = 0;  // the frames before this one in a row with its view and objects
  std::vector<FrameTiming> completed;  // collected, not yet returned
  glm::vec3 origin{0.0f};  // the render space's origin in world space (raybudget::renderOrigin)

  Impl(const HostDevice& host, const Scene& s, const RenderSettings& rs, const testing::Checks& checks)
      : settings(rs),
        deadlineTicks(checks.stageDeadlineTicks),
        fillDeadlineTicks(checks.fillDeadlineTicks),
        effects(raybudget::sceneEffects(s, rs.rayTracing.maxRoughness)),
        ssrUseful(raybudget::sceneEffects(s, RB_SSR_MAX_ROUGHNESS).reflections),
        sunDirection(sunOf(s)),
        ctx(host),
        scene(passes::uploadScene(ctx, s, rs)),
        targets(passes::createFrameTargets(ctx, rs.width, rs.height, scene.shadows, rs.shadowMapSize, rs.environmentMap, scene.lightCount,
                                           uint32_t(raybudget::reflectionProbesOf(s).size()),
                                           {.behindGlass = rs.screenSpaceTransmission && passes::GBufferPass::anyTransmissive(scene),
                                            .screenReflections = rs.screenSpaceReflections && ssrUseful,
                                            .fillHistory = needsFillHistory(rs.rayTracing.rate, effects),
                                            .shadowHistory = needsShadowHistory(rs.rayTracing.rate, rs.rayTracing, scene.lightCount),
                                            .layers = scene.hasLayers})),
        samplers(passes::createSamplers(ctx)),
        layouts(ctx, uint32_t(scene.textures.size()), native(), kFramesInFlight),
        timestamps(ctx, kFramesInFlight, kPassCount),
        selection(ctx, layouts, s, rs, kFramesInFlight, checks.selectionAgainstCpu),
        gbuffer(ctx, layouts),
        environment(ctx, layouts),
        probes(ctx, layouts, raybudget::reflectionProbesOf(s), scene.tracer->shader(passes::TraceShader::ReflectionProbe)),
        screenReflections(ctx, layouts),
        ssrReach(std::max(glm::length(s.boundsMax - s.boundsMin), 1e-3f)),
        lighting(ctx, layouts, kSpirv_lighting_comp),
        compose(ctx, layouts, kSpirv_compose_comp),
        behindGlassCopy(ctx, layouts, kSpirv_behind_glass_comp),
        traceShadows(ctx, layouts, scene.tracer->shader(passes::TraceShader::Shadows), passes::TileList::Shadows),
        traceEffects(ctx, layouts, scene.tracer->shader(passes::TraceShader::Effects), passes::TileList::Effects, tracedPaths()),
        fillEffects(ctx, layouts, kSpirv_fill_effects_comp, passes::TileList::EffectFill) {
    if (passes::ShadowMapPass::needed(scene)) shadowMaps.emplace(ctx, layouts, scene.shadows, targets, rs.shadowSlopeBias);
    for (Slot& slot : slots) {
      slot.uniforms = vk::createBuffer(ctx, sizeof(gpu::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
      slot.gbuffer = targets.gbufferViews();
      layouts.writeAll(uint32_t(&slot - slots), [&](VkDescriptorSet set, std::span<const uint32_t> bindings) {
        passes::writeSet(ctx, set, bindings, slot.uniforms, scene, targets, slot.gbuffer, selection.buffers(), samplers);
      });
    }
    // Storage images live in GENERAL; shadow maps start readable so that unused layers are valid.
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      for (const vk::Image* img : {&targets.direct, &targets.reflection, &targets.refraction, &targets.hdr, &targets.ldr, &targets.shadowMask,
                                   &targets.tracedMask, &targets.fillHistory, &targets.shadowHistory})
        vk::imageBarrier(cmd, *img, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
      passes::ShadowMapPass::initialize(cmd, targets);
      passes::ReflectionProbePass::initialize(cmd, targets);
      passes::ScreenReflectionPass::initialize(cmd, targets);
      vk::imageBarrier(cmd, targets.behindGlass, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
  }

  // The sky's sun follows the scene's first directional light, else a default elevation.
  static glm::vec3 sunOf(const Scene& s) {
    for (const Light& l : s.lights)
      if (l.type == LightType::Directional) return -l.direction;
    return glm::normalize(glm::vec3(0.3f, 1.0f, 0.4f));
  }

  // The timings and the selection's read-backs of the slot's completed frame.
  FrameTiming collect(Slot& slot) {
    FrameTiming t;
    t.frame = slot.frame;
    t.tlasRebuildMs = slot.tlasRebuildMs;
    t.shadowMapViews = slot.shadowMapsRecorded.views;
    t.shadowMapDraws = slot.shadowMapsRecorded.draws;
    t.shadowMapTexels = slot.shadowMapsRecorded.texels;
    t.probesCaptured = slot.probesCaptured;
    t.stillFrames = slot.stillFrames;
    t.coverageReused = slot.coverageReused;
    t.skipped = slot.skipped;
    const uint32_t s = uint32_t(&slot - slots);
    const auto ms = timestamps.read(s);
    for (size_t p = 0; p < kPassCount; ++p) t.passMs[p] = ms[p];
    selection.retire(s, settings, t);
    return t;
  }

  void writeUniforms(Slot& slot, const Camera& camera) {
    gpu::FrameUniforms u{};
    const float aspect = float(settings.width) / float(settings.height);
    u.view = camera.view();
    u.proj = camera.projection(aspect);
    u.viewProj = u.proj * u.view;
    u.invViewProj = glm::inverse(u.viewProj);
    u.cameraPositionNear = glm::vec4(camera.position, camera.znear);
    u.sizeLightsFrame = glm::uvec4(settings.width, settings.height, scene.lightCount, uint32_t(frameIndex));
    u.sunDirection = glm::vec4(sunDirection, settings.skyIntensity);
    u.exposure = glm::vec4(settings.exposure, settings.rayTracing.shadowUncertaintyTexels, slot.behindGlass == PassSkip::None ? 1.0f : 0.0f,
                           slot.gbuffer.layers ? 1.0f : 0.0f);
    u.rayTracing = glm::uvec4(tracedEffects(), settings.rayTracing.depth, std::bit_cast<uint32_t>(settings.rayTracing.maxRoughness),
                              itemFlags() | (reducedRates() ? RB_RT_RATES : 0u) |
                                  (reducedRates() && settings.rayTracing.temporalFill ? RB_RT_TEMPORAL_FILL : 0u));
    probes.writeUniforms(u, settings.reflectionProbes);
    u.previousViewProj = previousViewProj.value_or(u.viewProj);
    u.previousCamera = glm::vec4(previousCamera, previousViewProj ? 1.0f : 0.0f);
    u.ssr = glm::vec4(slot.ssr == PassSkip::None ? 1.0f : 0.0f, RB_SSR_MAX_ROUGHNESS, ssrReach, 0.0f);
    glm::uvec3 deadlines = selection.deadlineTicks(settings);
    if (deadlineTicks != 0) deadlines = {deadlineTicks, deadlineTicks, deadlines.z};
    if (fillDeadlineTicks != 0) deadlines.z = fillDeadlineTicks;
    u.stageDeadline = glm::uvec4(deadlines, 0u);
    std::memcpy(slot.uniforms.mapped, &u, sizeof(u));
  }

  // RB_RT_REFLECTIONS / RB_RT_REFRACTIONS: the paths switched on that the scene can show, all
  // the effects pass's pipelines hold.
  uint32_t tracedPaths() const {
    const RayTracingSettings& rt = settings.rayTracing;
    return (rt.reflections && effects.reflections ? RB_RT_REFLECTIONS : 0u) | (rt.refractions && effects.refractions ? RB_RT_REFRACTIONS : 0u);
  }

  // RB_RT_* bits of the effects traced this frame: those switched on that the scene can show;
  // with policy none, nothing.
  uint32_t tracedEffects() const {
    if (settings.policy == Policy::None || stageSkipped) return 0u;
    return (settings.rayTracing.shadows && effects.shadows ? RB_RT_SHADOWS : 0u) | tracedPaths();
  }

  // Why a trace pass for `bits` (RB_RT_*) is left out of the frame (PassSkip::None: it runs).
  PassSkip traceSkip(uint32_t bits, bool sceneHasIt) const {
    if (tracedEffects() & bits) return PassSkip::None;
    if (settings.policy == Policy::None) return PassSkip::PolicyTracesNothing;
    if (stageSkipped) return PassSkip::BudgetBelowFixedCost;
    if (!sceneHasIt) return bits == RB_RT_SHADOWS ? PassSkip::NoLights : PassSkip::NoSmoothOrTransmissiveMaterial;
    return PassSkip::EffectsOff;
  }

  // RB_RT_CLASSIFY_SHADOWS / RB_RT_MEASURE_ITEMS / RB_RT_SHORTEN_SHADOW_RAYS for the item-aware
  // policies: the shadow pass traces only where the shadow map is uncertain and ends its rays
  // past the map's nearest blocker, and the trace and lighting passes count each item's work
  // and the display error its tracing removed.
  uint32_t itemFlags() const {
    if (settings.policy != Policy::Benefit && settings.policy != Policy::Classified) return 0u;
    const RayTracingSettings& rt = settings.rayTracing;
    const bool classify = rt.classifyShadows && settings.benefitAblation != BenefitAblation::NoClassifier;
    // The nearest depth a shortened ray ends past covers a blocker's slope-scaled bias up to two
    // texels' slope (shadows.glsl, shadowRayEnd): with more, the rays run to the light.
    const bool shorten = rt.shortenShadowRays && settings.shadowSlopeBias <= 2.0f;
    return (classify ? RB_RT_CLASSIFY_SHADOWS : 0u) | RB_RT_MEASURE_ITEMS | (shorten ? RB_RT_SHORTEN_SHADOW_RAYS : 0u);
  }

  // Why the opaque frame behind glass is not lit this frame (PassSkip::None: it is): a host's
  // G-buffer holds the glass already; without glass in view nothing shows it; where `all`
  // traces every transmissive pixel's refraction nothing falls back to it (`classified`
  // traces them all too, but measures each item's error against the fallback).
  PassSkip behindGlassSkip(bool hostGBuffer, const glm::mat4& viewProj, glm::uvec4& rect) const {
    if (hostGBuffer) return PassSkip::HostGBuffer;
    if (!settings.screenSpaceTransmission) return PassSkip::FallbackOff;
    const std::optional<glm::uvec4> r = passes::GBufferPass::transmissiveRect(scene, viewProj, settings.width, settings.height);
    if (!r) return PassSkip::NoTransmissionInView;
    rect = *r;
    if (everyPixelTraces(RB_RT_REFRACTIONS)) return PassSkip::EveryPixelTracesRefractions;
    return PassSkip::None;
  }

  // Why smooth surfaces do not reflect what is on screen this frame (PassSkip::None: they do).
  PassSkip ssrSkip() const {
    if (!settings.screenSpaceReflections) return PassSkip::FallbackOff;
    if (!ssrUseful) return PassSkip::NoSmoothMaterial;
    if (everyPixelTraces(RB_RT_REFLECTIONS) && settings.rayTracing.maxRoughness >= RB_SSR_MAX_ROUGHNESS)
      return PassSkip::EveryPixelTracesReflections;
    if (!previousViewProj) return PassSkip::NoPreviousFrame;
    return PassSkip::None;
  }

  // Whether `all` at full rate traces the effect (an RB_RT_* bit) at every pixel that shows it,
  // so that no pixel falls back for it.
  bool everyPixelTraces(uint32_t effect) const {
    return (tracedEffects() & effect) && settings.policy == Policy::All && !reducedRates();
  }

  // Whether selected items are traced at a reduced rate (the policies that select items).
  bool reducedRates() const {
    const Policy p = settings.policy;
    const ItemRate r = settings.rayTracing.rate;
    return r != ItemRate::Full && (p == Policy::Benefit || ((p == Policy::All || p == Policy::Classified) && r != ItemRate::Auto));
  }

  // Zeroes the traced mask before the trace passes mark it; a frame that traces nothing
  // clears it only when an earlier one left marks.
  void clearTracedMask(VkCommandBuffer cmd) {
    const VkClearColorValue zero{};
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, targets.tracedMask.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }

  void computeToCompute(VkCommandBuffer cmd) {
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }

  bool native() const { return scene.tracer->kind() == Tracer::Native; }

  // The object records for the moved objects' new transforms (and their culling spheres);
  // the shadow maps and reflection probes that see a moved object before or after are
  // rendered again.
  std::vector<gpu::GpuObject> refreshObjectRecords() {
    std::vector<gpu::GpuObject> objects;
    for (const Object& o : scene.shell.objects) objects.push_back(passes::gpuObject(scene, o));
    for (size_t i = 0; i < objects.size(); ++i) {
      const glm::vec4 before = scene.objectSpheres[i];
      scene.objectSpheres[i] = objects[i].boundsCenterRadius;
      if (before == scene.objectSpheres[i]) continue;
      if (shadowMaps) shadowMaps->objectMoved(scene.shadows, before, scene.objectSpheres[i]);
      probes.objectMoved(before, scene.objectSpheres[i]);
    }
    return objects;
  }

  // Points the G-buffer bindings of the slot's sets at `g` when they read other views. The
  // slot's previous frame has completed (its fence, or recordFrame's contract).
  void bindGBuffer(Slot& slot, const GBuffer& g) {
    const GBuffer& b = slot.gbuffer;
    if (b.depth == g.depth && b.normal == g.normal && b.baseMetal == g.baseMetal && b.roughTransIor == g.roughTransIor &&
        b.emissive == g.emissive && b.objectId == g.objectId && b.materialId == g.materialId && b.position == g.position && b.layout == g.layout &&
        b.layers == g.layers)
      return;
    slot.gbuffer = g;
    layouts.writeAll(uint32_t(&slot - slots), [&](VkDescriptorSet set, std::span<const uint32_t> bindings) {
      std::vector<uint32_t> gbufferOnly;
      for (uint32_t x : bindings)
        if (passes::isGBufferBinding(x)) gbufferOnly.push_back(x);
      passes::writeSet(ctx, set, gbufferOnly, slot.uniforms, scene, targets, g, selection.buffers(), samplers);
    });
  }

  // Glass shows the opaque frame behind it (Filament's and three.js's screen-space
  // transmission): the opaque G-buffer lit with the shadow maps and the environment fallback
  // at every second pixel of the rectangle around the glass, summed into the half-resolution
  // behind-glass image with a blitted mip chain, then the transmissive draws over the opaque
  // G-buffer.
  void recordBehindGlass(const passes::FrameContext& fc, const glm::uvec4& rect) {
    VkCommandBuffer cmd = fc.cmd;
    constexpr uint32_t kStride = 2;  // half resolution
    lighting.recordOver(fc, RB_PASS_BEHIND_GLASS, rect, kStride);
    // Cleared to 0 (in front of everything: the environment) outside the rectangle.
    const vk::Image& img = targets.behindGlass;
    vk::imageBarrier(cmd, img, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    const VkClearColorValue zero{};
    const VkImageSubresourceRange mip0{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &mip0);
    vk::imageBarrier(cmd, img, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    computeToCompute(cmd);
    behindGlassCopy.recordOver(fc, RB_PASS_BEHIND_GLASS, rect, kStride);
    vk::imageBarrier(cmd, img, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    vk::generateMips(cmd, img);
    gbuffer.record(fc, passes::GBufferPass::Draws::Transmissive);
  }

  // The frame's commands into `cmd`; `hostGBuffer`: the slot's sets read a host's G-buffer,
  // so no raster.
  void recordCommands(Slot& slot, VkCommandBuffer cmd, const glm::mat4& viewProj, bool hostGBuffer) {
    const uint32_t s = uint32_t(&slot - slots);
    timestamps.reset(cmd, s);
    // Frames share their images: order this frame after everything the previous one did.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    // Moved objects: the tracer's structures and the object records follow, uploaded from the
    // slot's staging buffer after the previous frame's reads (the frame-start barrier).
    slot.tlasRebuildMs = 0.0;
    if (objectsMoved) {
      objectsMoved = false;
      const std::vector<gpu::GpuObject> records = refreshObjectRecords();
      slot.tlasRebuildMs = scene.tracer->recordMovedObjects(cmd, scene.shell, records, slot.updateStaging, scene.objects);
    }
    const passes::FrameContext fc{cmd, s, scene, targets, selection.buffers(), viewProj};
    auto timed = [&](Pass pass, auto&& body) {
      timestamps.begin(cmd, s, uint32_t(pass));
      body();
      timestamps.end(cmd, s, uint32_t(pass));
    };
    // Each pass either runs (timed) or is left out with its reason.
    auto run = [&](Pass pass, PassSkip skip, auto&& body) {
      slot.skipped[size_t(pass)] = skip;
      if (skip == PassSkip::None) timed(pass, body);
    };
    // Skip what the frame does not need: no shadow maps when every pixel traces its
    // shadows, no trace work when nothing is traced, and the trace passes run only over the
    // tiles holding selected pixels (an empty tile list is an empty indirect dispatch).
    const uint32_t traced = tracedEffects();
    selection.beginFrame(cmd, s);
    const bool behindGlass = slot.behindGlass == PassSkip::None;
    run(Pass::GBuffer, hostGBuffer ? PassSkip::HostGBuffer : PassSkip::None,
        [&] { gbuffer.record(fc, behindGlass ? passes::GBufferPass::Draws::Opaque : passes::GBufferPass::Draws::All); });
    // With a budgeted policy unselected objects keep the shadow maps; at a reduced rate the
    // shadow fill corrects the maps (rt_shadows.comp); the opaque frame behind glass is lit
    // with them.
    const bool everyPixelTracesShadows = everyPixelTraces(RB_RT_SHADOWS) && !behindGlass;
    slot.shadowMapsRecorded = {};
    run(Pass::ShadowMaps,
        !shadowMaps                ? PassSkip::NoLights
        : everyPixelTracesShadows  ? PassSkip::EveryPixelTracesShadows
        : !shadowMaps->anyStale()  ? PassSkip::ShadowMapsCurrent
                                   : PassSkip::None,
        [&] { slot.shadowMapsRecorded = shadowMaps->record(fc); });
    run(Pass::Environment, environmentReady ? PassSkip::EnvironmentReady : PassSkip::None, [&] { environment.record(fc); });
    environmentReady = true;
    // The probes are shaded with the environment and the traced shadows of their own rays.
    slot.probesCaptured = 0;
    run(Pass::ReflectionProbes,
        !settings.reflectionProbes   ? PassSkip::FallbackOff
        : probes.probes().empty()    ? PassSkip::NoReflectionProbe
        : !probes.anyStale()         ? PassSkip::ProbesCurrent
                                     : PassSkip::None,
        [&] { slot.probesCaptured = probes.record(fc); });
    run(Pass::BehindGlass, slot.behindGlass, [&] { recordBehindGlass(fc, slot.behindGlassRect); });
    // After the transmissive draws: the reflections see the G-buffer the frame shows.
    run(Pass::ScreenSpaceReflections, slot.ssr, [&] {
      screenReflections.record(fc);
      computeToCompute(cmd);
    });
    // The classifier's counts are the items' pixels for `benefit`; otherwise only objectMetrics reads them.
    const bool classify = settings.objectMetrics || (traced && settings.policy == Policy::Benefit);
    const PassSkip nothingTraced = settings.policy == Policy::None ? PassSkip::PolicyTracesNothing
                                   : stageSkipped                  ? PassSkip::BudgetBelowFixedCost
                                                                   : PassSkip::NoEffectInScene;
    // On a still view the coverage buffers hold what the frame before counted, if it counted
    // with the same classifier on the G-buffer this frame draws (not a host's, which may differ).
    // Every kRecountStillCoverage-th still frame counts anyway, so that the counted frames'
    // overhead (TimeScale::overheadMs) stays current through a still view.
    const bool countCoverage = settings.objectMetrics || traced;
    slot.coverageReused = countCoverage && settings.reuseStillCoverage && !hostGBuffer && stillFrames % kRecountStillCoverage != 0 &&
                          coverageCounted && coverageClassified == classify;
    run(Pass::Coverage, countCoverage ? PassSkip::None : nothingTraced,
        [&] { selection.recordCoverage(fc, classify, slot.coverageReused); });
    coverageCounted = countCoverage;
    coverageClassified = classify;
    if (traced) computeToCompute(cmd);
    // The mask's clear is the select pass's (the stage's fixed cost).
    if (!traced && tracedMaskWritten) clearTracedMask(cmd);
    run(Pass::Select, traced ? PassSkip::None : nothingTraced, [&] {
      clearTracedMask(cmd);
      selection.recordSelect(fc, s, settings, stillFrames, slot.coverageReused);
    });
    tracedMaskWritten = traced != 0;
    // Shadows at a reduced ray rate are filled in the lighting pass (shaders/include/shadow_fill.glsl),
    // reflections and refractions in a pass of their own after the effects pass (fill_effects.comp).
    run(Pass::TraceShadows, traceSkip(RB_RT_SHADOWS, effects.shadows), [&] { traceShadows.recordOverTiles(fc); });
    // The lighting pass also writes the environment fallback for reflections and refractions,
    // and where no reflection or refraction is traced after it, the composed frame.
    computeToCompute(cmd);
    const PassSkip effectsSkip = traceSkip(RB_RT_REFLECTIONS | RB_RT_REFRACTIONS, effects.reflections || effects.refractions);
    const bool composeInLighting = effectsSkip != PassSkip::None;
    timed(Pass::Lighting, [&] { lighting.record(fc, composeInLighting ? RB_PASS_COMPOSE : 0u); });
    if (effectsSkip == PassSkip::None) computeToCompute(cmd);
    run(Pass::TraceEffects, effectsSkip, [&] { traceEffects.recordOverTiles(fc); });
    computeToCompute(cmd);
    const PassSkip fillSkip = effectsSkip != PassSkip::None ? effectsSkip : reducedRates() ? PassSkip::None : PassSkip::FullRate;
    run(Pass::FillEffects, fillSkip, [&] {
      fillEffects.recordOverTiles(fc);
      computeToCompute(cmd);
    });
    run(Pass::Compose, composeInLighting ? PassSkip::ComposedInLighting : PassSkip::None, [&] { compose.record(fc); });
    selection.recordStats(cmd, s);
  }

  // The slot's previous frame has completed by the host's contract.
  void recordFrame(VkCommandBuffer cmd, const Camera& camera, const GBuffer* host) {
    if (!cmd) throw Error("recordFrame: no command buffer");
    validateCamera(camera, "recordFrame");
    if (host) {
      const GBuffer& g = *host;
      for (VkImageView v : {g.depth, g.normal, g.baseMetal, g.roughTransIor, g.emissive, g.objectId, g.materialId, g.position})
        if (!v) throw Error("recordFrame: every G-buffer view must be set (core::GBuffer)");
      if (g.layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL && g.layout != VK_IMAGE_LAYOUT_GENERAL)
        throw Error("recordFrame: the G-buffer's layout must be SHADER_READ_ONLY_OPTIMAL or GENERAL");
    }
    Slot& slot = slots[frameIndex % kFramesInFlight];
    if (slot.recorded) completed.push_back(collect(slot));
    bindGBuffer(slot, host ? *host : targets.gbufferViews());
    const float aspect = float(settings.width) / float(settings.height);
    const glm::mat4 viewProj = camera.projection(aspect) * camera.view();
    stillFrames = previousViewProj == viewProj && !objectsMoved ? stillFrames + 1 : 0;
    slot.stillFrames = stillFrames;
    if (shadowMaps && settings.shadowMapsFitScreen)
      shadowMaps->fit(scene.shadows, viewProj, camera.position, 0.5f * float(settings.height) / std::tan(0.5f * camera.yfov));
    // A budget the stage's fixed cost alone exceeds buys nothing: the whole stage is left out.
    stageSkipped = selection.skipsStage(frameIndex % kFramesInFlight, settings);
    slot.behindGlass = behindGlassSkip(host != nullptr, viewProj, slot.behindGlassRect);
    slot.ssr = ssrSkip();
    writeUniforms(slot, camera);
    recordCommands(slot, cmd, viewProj, host != nullptr);
    previousViewProj = viewProj;
    previousCamera = camera.position;
    slot.recorded = true;
    slot.frame = frameIndex++;
  }

  // Every recorded frame has completed (the host says so): their timings, oldest first.
  void collectAll() {
    for (uint32_t k = 0; k < kFramesInFlight; ++k) {
      Slot& slot = slots[(frameIndex + k) % kFramesInFlight];
      if (slot.recorded) {
        completed.push_back(collect(slot));
        slot.recorded = false;
      }
    }
  }

  // Forgets what the selection learned (S, work per pixel) and switches policy and budget;
  // the time scale learned so far for the new policy's cost unit is kept (the prior if none).
  void restartSelection(Policy policy, float budgetMs, BenefitAblation ablation, ItemRate rate) {
    RenderSettings next = settings;
    next.policy = policy;
    next.budgetMs = budgetMs;
    next.benefitAblation = ablation;
    next.rayTracing.rate = rate;
    validateSettings(next);
    if (needsFillHistory(rate, effects) && !targets.needs.fillHistory)
      throw Error("restartSelection: a reduced ray rate needs the fill's history, which is made only when the renderer is made with a reduced "
                  "RayTracingSettings::rate");
    if (needsShadowHistory(rate, next.rayTracing, scene.lightCount) && !targets.needs.shadowHistory)
      throw Error("restartSelection: a reduced ray rate needs the shadow fill's history, which is made only when the renderer is made with a "
                  "reduced RayTracingSettings::rate");
    collectAll();
    settings = next;
    selection.restart(settings);
    coverageCounted = false;
  }

  void setCostModel(const CostModel& m) {
    for (double v : {m.msPerWorkUnit, m.msPerPaperCost, m.msPerItemWorkUnit, m.stageOverheadMs, m.traceFixedMs, m.msPerRay, m.msPerItemRay})
      if (!std::isfinite(v) || v < 0.0 || v > 1e6) throw Error("cost model values must be finite and within 0..1e6, got " + std::to_string(v));
    selection.setCostModel(m);
  }

};

Context::Context(const HostDevice& host, const Scene& scene, const RenderSettings& settings) : Context(host, scene, settings, testing::Checks{}) {}

Context::Context(const HostDevice& host, const Scene& scene, const RenderSettings& settings, const testing::Checks& checks) {
  validateSettings(settings);
  const glm::vec3 origin = raybudget::renderOrigin(scene);
  if (origin == glm::vec3(0.0f)) impl_ = std::make_unique<Impl>(host, scene, settings, checks);  // no copy
  else impl_ = std::make_unique<Impl>(host, inRenderSpace(scene, origin), settings, checks);
  impl_->origin = origin;
}

Context::~Context() = default;

void Context::recordFrame(VkCommandBuffer commandBuffer, const Camera& camera, const GBuffer* gbuffer) {
  impl_->recordFrame(commandBuffer, inRenderSpace(camera, impl_->origin), gbuffer);
}

std::vector<FrameTiming> Context::completedFrames(bool everyRecordedFrameCompleted) {
  if (everyRecordedFrameCompleted) impl_->collectAll();
  return std::exchange(impl_->completed, {});
}

FrameOutputs Context::outputs() const {
  const passes::FrameTargets& t = impl_->targets;
  FrameOutputs o;
  o.hdr = t.hdr.image;
  o.ldr = t.ldr.image;
  o.hdrView = t.hdr.view;
  o.ldrView = t.ldr.view;
  o.direct = t.direct.image;
  o.reflection = t.reflection.image;
  o.refraction = t.refraction.image;
  o.directView = t.direct.view;
  o.reflectionView = t.reflection.view;
  o.refractionView = t.refraction.view;
  o.shadowVisibility = t.shadowMask.image;
  o.shadowVisibilityLayers = t.shadowMask.desc.layers / 2;  // (the second half: the fill's, frame_targets.h)
  o.tracedMask = t.tracedMask.image;
  o.tracedMaskView = t.tracedMask.view;
  return o;
}

OwnGBuffer Context::ownGBuffer() const {
  const passes::FrameTargets& t = impl_->targets;
  return {t.depth.image, t.normal.image, t.baseMetal.image, t.roughTransIor.image, t.emissive.image, t.objectId.image, t.materialId.image,
          t.position.image, t.layers.image};
}

void Context::restartSelection(Policy policy, float budgetMs, BenefitAblation ablation, ItemRate rate) {
  impl_->restartSelection(policy, budgetMs, ablation, rate);
}

void Context::setBudget(float budgetMs) {
  RenderSettings next = impl_->settings;
  next.budgetMs = budgetMs;
  validateSettings(next);
  impl_->settings.budgetMs = budgetMs;
}

CostModel Context::costModel() const { return impl_->selection.costModel(); }

void Context::setCostModel(const CostModel& model) { impl_->setCostModel(model); }

void Context::setObjectParams(uint32_t objectId, const RayBudgetParams& params) {
  Scene& shell = impl_->scene.shell;
  if (objectId >= shell.objects.size())
    throw Error("setObjectParams: no object " + std::to_string(objectId) + " (the scene has " + std::to_string(shell.objects.size()) + ")");
  validateRayBudgetParams(params, "object " + std::to_string(objectId) + " ('" + shell.objects[objectId].name + "')");
  shell.objects[objectId].params = params;
  const select::ObjectParams p = select::objectParams(shell, shell.objects[objectId], impl_->settings.rayTracing.maxRoughness);
  impl_->selection.setObjectParams(objectId, p.K, p.Q, p.I);
}

RayBudgetParams Context::objectParams(uint32_t objectId) const {
  const Scene& shell = impl_->scene.shell;
  if (objectId >= shell.objects.size()) throw Error("objectParams: no object " + std::to_string(objectId));
  const select::ObjectParams p = select::objectParams(shell, shell.objects[objectId], impl_->settings.rayTracing.maxRoughness);
  return {p.K, p.Q, p.I};
}

glm::vec3 Context::renderOrigin() const { return impl_->origin; }

void Context::setObjectTransform(uint32_t objectId, const glm::mat4& transform) {
  raybudget::setObjectTransform(impl_->scene.shell, objectId, inRenderSpace(transform, impl_->origin));
  impl_->objectsMoved = true;
}

std::vector<ObjectMetrics> Context::objectMetrics() const {
  if (!impl_->settings.objectMetrics) throw Error("objectMetrics() needs RenderSettings::objectMetrics");
  if (impl_->frameIndex == 0) throw Error("objectMetrics() before any frame was rendered");
  return impl_->selection.objectMetrics();
}

AccelStats Context::accelStats() const { return impl_->scene.tracer->stats(); }

SceneEffects Context::sceneEffects() const { return impl_->effects; }

uint64_t Context::allocatedBytes() const { return impl_->ctx.allocatedBytes(); }

std::vector<std::string> Context::builtPipelines() const {
  const Impl& r = *impl_;
  std::vector<std::string> out = {"gbuffer", "coverage", "select", "environment", "lighting", "compose"};
  if (r.shadowMaps) out.push_back("shadow_maps");
  if (r.probes.built()) out.push_back("reflection_probes");
  if (r.screenReflections.built()) out.push_back("ssr");
  if (r.traceShadows.built()) out.push_back("trace_shadows");
  // The effects pass's pipelines by the paths they hold: trace_effects(reflections), ...
  const uint32_t paths = r.traceEffects.paths();
  const std::string effects = std::string("trace_effects(") + (paths & RB_RT_REFLECTIONS ? "reflections" : "") +
                              (paths == (RB_RT_REFLECTIONS | RB_RT_REFRACTIONS) ? "," : "") + (paths & RB_RT_REFRACTIONS ? "refractions" : "") + ")";
  if (r.traceEffects.built()) out.push_back(effects);
  if (r.fillEffects.built()) out.push_back("fill_effects");
  return out;
}

uint64_t Context::framesRecorded() const { return impl_->frameIndex; }

}  // namespace raybudget::core
