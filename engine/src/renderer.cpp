// The frame: G-buffer -> shadow maps -> (environment, once) -> lighting + environment
// fallback -> compose, two frames in flight, every pass bracketed by timestamps.
#include "raybudget/renderer.h"
#include "raybudget/testing.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>

#include "compose_comp.h"
#include "env_fallback_comp.h"
#include "lighting_comp.h"
#include "passes/descriptors.h"
#include "passes/environment.h"
#include "passes/frame_targets.h"
#include "passes/gbuffer.h"
#include "passes/scene_gpu.h"
#include "passes/screen_pass.h"
#include "passes/trace_pass.h"
#include "passes/shadow_maps.h"
#include "select/selection_stage.h"
#include "shared/config.h"
#include "shared/types.h"
#include "vk/check.h"
#include "vk/context.h"
#include "vk/timestamps.h"

namespace raybudget {

const char* policyName(Policy policy) {
  return policy == Policy::Classified ? "classified" : select::policyName(select::toSelectPolicy(policy));
}

Policy parsePolicy(const std::string& name) {
  if (name == "classified") return Policy::Classified;
  const select::Policy p = select::parsePolicy(name);
  for (Policy q : {Policy::None, Policy::All, Policy::Paper, Policy::Density, Policy::Nearest, Policy::Random, Policy::Benefit})
    if (select::toSelectPolicy(q) == p) return q;
  throw Error("the optimal policy runs on the CPU for benchmarks only; render with another and --optimal-bound for its bound");
}

const char* ablationName(BenefitAblation a) {
  switch (a) {
    case BenefitAblation::None: return "";
    case BenefitAblation::NoCentrality: return "no-centrality";
    case BenefitAblation::NoHysteresis: return "no-hysteresis";
    case BenefitAblation::PriorOnly: return "prior-only";
    case BenefitAblation::NoClassifier: return "no-classifier";
    case BenefitAblation::NoProbe: return "no-probe";
  }
  return "?";
}

BenefitAblation parseAblation(const std::string& name) {
  for (BenefitAblation a : {BenefitAblation::NoCentrality, BenefitAblation::NoHysteresis, BenefitAblation::PriorOnly, BenefitAblation::NoClassifier,
                            BenefitAblation::NoProbe})
    if (name == ablationName(a)) return a;
  throw Error("unknown benefit ablation '" + name + "' (no-centrality, no-hysteresis, prior-only, no-classifier, no-probe)");
}

bool isBudgeted(Policy policy) { return policy != Policy::None && policy != Policy::All && policy != Policy::Classified; }
const char* tracerName(Tracer tracer) { return tracer == Tracer::Native ? "native" : "compute"; }

const char* itemRateName(ItemRate rate) {
  switch (rate) {
    case ItemRate::Half: return "half";
    case ItemRate::Quarter: return "quarter";
    case ItemRate::Auto: return "auto";
    case ItemRate::Full: break;
  }
  return "full";
}

ItemRate parseItemRate(const std::string& name) {
  for (ItemRate r : {ItemRate::Full, ItemRate::Half, ItemRate::Quarter, ItemRate::Auto})
    if (name == itemRateName(r)) return r;
  throw Error("unknown ray rate '" + name + "' (full, half, quarter, auto)");
}

const char* passSkipText(PassSkip skip) {
  switch (skip) {
    case PassSkip::None: return "";
    case PassSkip::PolicyTracesNothing: return "the policy traces nothing";
    case PassSkip::NoEffectInScene: return "the scene has nothing the switched-on effects could trace";
    case PassSkip::EffectsOff: return "its effects are switched off";
    case PassSkip::NoLights: return "no light (with a shadow map) in the scene";
    case PassSkip::NoSmoothOrTransmissiveMaterial: return "no material smooth enough to reflect or transmissive";
    case PassSkip::EveryPixelTracesShadows: return "every pixel traces its shadows";
    case PassSkip::EnvironmentReady: return "the static environment is built";
    case PassSkip::HostGBuffer: return "the host rasterised the G-buffer";
  }
  return "?";
}

const char* passName(Pass pass) {
  switch (pass) {
    case Pass::GBuffer: return "gbuffer";
    case Pass::Coverage: return "coverage";
    case Pass::Select: return "select";
    case Pass::ShadowMaps: return "shadow_maps";
    case Pass::Environment: return "environment";
    case Pass::TraceShadows: return "trace_shadows";
    case Pass::TraceEffects: return "trace_effects";
    case Pass::EnvFallback: return "env_fallback";
    case Pass::Lighting: return "lighting";
    case Pass::Compose: return "compose";
    case Pass::Count: break;
  }
  return "?";
}

double FrameTiming::totalMs() const {
  double sum = 0.0;
  for (const auto& ms : passMs) sum += ms.value_or(0.0);
  return sum;
}

double FrameTiming::traceMs() const {
  double ms = 0.0;
  for (Pass p : {Pass::TraceShadows, Pass::TraceEffects}) ms += passMs[size_t(p)].value_or(0.0);
  return ms;
}

double FrameTiming::rtStageMs() const {
  return passMs[size_t(Pass::Coverage)].value_or(0.0) + passMs[size_t(Pass::Select)].value_or(0.0) + traceMs();
}

namespace {

constexpr uint32_t kFramesInFlight = 2;

void validateSettings(const RenderSettings& s) {
  if (s.width == 0 || s.height == 0 || s.width > 16384 || s.height > 16384)
    throw Error("render size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " is outside 1..16384");
  if (s.shadowMapSize < 16 || s.shadowMapSize > 8192) throw Error("shadow map size must be within 16..8192");
  if (!std::isfinite(s.exposure) || s.exposure <= 0.0f) throw Error("exposure must be a positive finite number");
  if (!std::isfinite(s.skyIntensity) || s.skyIntensity < 0.0f) throw Error("sky intensity must be a non-negative finite number");
  if (isBudgeted(s.policy) && (!std::isfinite(s.budgetMs) || s.budgetMs <= 0.0f || s.budgetMs > 1e6f))
    throw Error("the trace budget must be a positive number of milliseconds (at most 1e6), got " + std::to_string(s.budgetMs));
  if (s.graphPointers > 64) throw Error("the paper's graph takes at most 64 relevance pointers per node");
  if (!std::isfinite(s.budgetConfidence) || s.budgetConfidence < 0.5f || s.budgetConfidence > 0.99f)
    throw Error("the budget's confidence (budgetConfidence) must be within 0.5..0.99, got " + std::to_string(s.budgetConfidence));
  if (!std::isfinite(s.probeShare) || s.probeShare < 0.0f || s.probeShare > 0.5f)
    throw Error("the probe's share of the budget (probeShare) must be within 0..0.5, got " + std::to_string(s.probeShare));
  if (!std::isfinite(s.rayTracing.maxRoughness) || s.rayTracing.maxRoughness < 0.0f || s.rayTracing.maxRoughness > 1.0f)
    throw Error("the ray-tracing roughness cut-off (maxRoughness) must be within 0..1, got " + std::to_string(s.rayTracing.maxRoughness));
  if (!std::isfinite(s.rayTracing.shadowUncertaintyTexels) || s.rayTracing.shadowUncertaintyTexels < 0.0f ||
      s.rayTracing.shadowUncertaintyTexels > 64.0f)
    throw Error("the shadow-map uncertainty reach (shadowUncertaintyTexels) must be within 0..64 texels, got " +
                std::to_string(s.rayTracing.shadowUncertaintyTexels));
  if (s.rayTracing.depth < 1 || s.rayTracing.depth > RB_RT_MAX_DEPTH)
    throw Error("ray-tracing depth must be within 1.." + std::to_string(RB_RT_MAX_DEPTH));
}

}  // namespace

struct Renderer::Impl {
  struct Slot {
    vk::Owned<VkCommandBuffer> cmd;
    vk::Owned<VkFence> fence;
    vk::Buffer uniforms;
    core::GBuffer gbuffer;  // the views the slot's sets read the G-buffer from
    bool recorded = false;  // recorded into a host's command buffer (recordFrame), not yet retired
    bool inFlight = false;
    uint64_t frame = 0;
    std::array<PassSkip, kPassCount> skipped{};  // why each pass not recorded was left out
    double tlasRebuildMs = 0.0;
    vk::Buffer updateStaging;  // moved objects: new TLAS nodes, instances and object records
  };

  RenderSettings settings;
  SceneEffects effects;  // what the scene can show at all: no pass, no pipeline for the rest
  glm::vec3 sunDirection;
  std::unique_ptr<vk::Context> context;  // the renderer's own device, or the host's borrowed
  vk::Context& ctx;
  passes::SceneGpu scene;
  passes::FrameTargets targets;
  passes::Samplers samplers;
  passes::PassLayouts layouts;  // each pass's descriptor set layout and per-slot sets
  vk::Owned<VkCommandPool> commandPool;
  vk::TimestampPool timestamps;
  // Coverage, select, the tile list and the cost model: the selection half of the stage.
  select::SelectionStage selection;
  passes::GBufferPass gbuffer;
  std::optional<passes::ShadowMapPass> shadowMaps;  // only when a light has a shadow map
  passes::EnvironmentPass environment;
  passes::ScreenPass lighting;
  passes::ScreenPass envFallback;
  passes::ScreenPass compose;
  passes::TracePass traceShadows;
  passes::TracePass traceEffects;
  Slot slots[kFramesInFlight];
  uint64_t frameIndex = 0;
  bool environmentReady = false;
  bool objectsMoved = false;

  Impl(const Scene& s, const RenderSettings& rs, std::unique_ptr<vk::Context> device, const testing::Checks& checks = {})
      : settings(rs),
        effects(raybudget::sceneEffects(s, rs.rayTracing.maxRoughness)),
        sunDirection(sunOf(s)),
        context(std::move(device)),
        ctx(*context),
        scene(passes::uploadScene(ctx, s, rs)),
        targets(passes::createFrameTargets(ctx, rs.width, rs.height, scene.shadows, rs.shadowMapSize, rs.environmentMap, scene.lightCount)),
        samplers(passes::createSamplers(ctx)),
        layouts(ctx, uint32_t(scene.textures.size()), native(), kFramesInFlight),
        commandPool(makeCommandPool()),
        timestamps(ctx, kFramesInFlight, kPassCount),
        selection(ctx, layouts, s, rs, kFramesInFlight, checks.selectionAgainstCpu),
        gbuffer(ctx, layouts),
        environment(ctx, layouts),
        lighting(ctx, layouts, kSpirv_lighting_comp),
        envFallback(ctx, layouts, kSpirv_env_fallback_comp),
        compose(ctx, layouts, kSpirv_compose_comp),
        traceShadows(ctx, layouts, scene.tracer->shader(passes::TraceShader::Shadows)),
        traceEffects(ctx, layouts, scene.tracer->shader(passes::TraceShader::Effects)) {
    if (passes::ShadowMapPass::needed(scene)) shadowMaps.emplace(ctx, layouts);
    for (Slot& slot : slots) {
      slot.cmd = allocateCommandBuffer();
      slot.fence = makeFence();
      slot.uniforms = vk::createBuffer(ctx, sizeof(gpu::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
      slot.gbuffer = targets.gbufferViews();
      layouts.writeAll(uint32_t(&slot - slots), [&](VkDescriptorSet set, std::span<const uint32_t> bindings) {
        passes::writeSet(ctx, set, bindings, slot.uniforms, scene, targets, slot.gbuffer, selection.buffers(), samplers);
      });
    }
    // Storage images live in GENERAL; shadow maps start readable so that unused layers are valid.
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      for (const vk::Image* img : {&targets.direct, &targets.indirect, &targets.hdr, &targets.ldr, &targets.shadowMask})
        vk::imageBarrier(cmd, *img, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
      passes::ShadowMapPass::initialize(cmd, targets);
    });
  }

  // The sky's sun follows the scene's first directional light, else a default elevation.
  static glm::vec3 sunOf(const Scene& s) {
    for (const Light& l : s.lights)
      if (l.type == LightType::Directional) return -l.direction;
    return glm::normalize(glm::vec3(0.3f, 1.0f, 0.4f));
  }

  vk::Owned<VkCommandPool> makeCommandPool() {
    VkCommandPoolCreateInfo ci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    ci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    ci.queueFamilyIndex = ctx.queueFamily();
    const VkDevice device = ctx.device();
    VkCommandPool p = VK_NULL_HANDLE;
    VK_CHECK(vkCreateCommandPool(device, &ci, nullptr, &p));
    return vk::Owned<VkCommandPool>(p, [device](VkCommandPool x) { vkDestroyCommandPool(device, x, nullptr); });
  }

  vk::Owned<VkCommandBuffer> allocateCommandBuffer() {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = commandPool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateCommandBuffers(ctx.device(), &ai, &cmd));
    const VkDevice device = ctx.device();
    const VkCommandPool p = commandPool;
    return vk::Owned<VkCommandBuffer>(cmd, [device, p](VkCommandBuffer c) { vkFreeCommandBuffers(device, p, 1, &c); });
  }

  vk::Owned<VkFence> makeFence() {
    VkFenceCreateInfo ci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    const VkDevice device = ctx.device();
    VkFence f = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFence(device, &ci, nullptr, &f));
    return vk::Owned<VkFence>(f, [device](VkFence x) { vkDestroyFence(device, x, nullptr); });
  }

  // Waits for the slot's previous frame (submitted kFramesInFlight frames ago) and collects
  // its timestamps.
  std::optional<FrameTiming> retire(Slot& slot) {
    if (!slot.inFlight) return std::nullopt;
    VkFence fence = slot.fence;
    VK_CHECK(vkWaitForFences(ctx.device(), 1, &fence, VK_TRUE, UINT64_MAX));
    VK_CHECK(vkResetFences(ctx.device(), 1, &fence));
    slot.inFlight = false;
    return collect(slot);
  }

  // The timings and the selection's read-backs of the slot's completed frame.
  FrameTiming collect(Slot& slot) {
    FrameTiming t;
    t.frame = slot.frame;
    t.tlasRebuildMs = slot.tlasRebuildMs;
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
    u.exposure = glm::vec4(settings.exposure, settings.rayTracing.shadowUncertaintyTexels, 0.0f, 0.0f);
    u.rayTracing = glm::uvec4(tracedEffects(), settings.rayTracing.depth, std::bit_cast<uint32_t>(settings.rayTracing.maxRoughness),
                              itemFlags() | (reducedRates() ? RB_RT_RATES : 0u));
    std::memcpy(slot.uniforms.mapped, &u, sizeof(u));
  }

  // RB_RT_* bits of the effects traced this frame: those switched on that the scene can show;
  // with policy none, nothing.
  uint32_t tracedEffects() const {
    if (settings.policy == Policy::None) return 0u;
    const RayTracingSettings& rt = settings.rayTracing;
    return (rt.shadows && effects.shadows ? RB_RT_SHADOWS : 0u) | (rt.reflections && effects.reflections ? RB_RT_REFLECTIONS : 0u) |
           (rt.refractions && effects.refractions ? RB_RT_REFRACTIONS : 0u);
  }

  // Why a trace pass for `bits` (RB_RT_*) is left out of the frame (PassSkip::None: it runs).
  PassSkip traceSkip(uint32_t bits, bool sceneHasIt) const {
    if (tracedEffects() & bits) return PassSkip::None;
    if (settings.policy == Policy::None) return PassSkip::PolicyTracesNothing;
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
    return (classify ? RB_RT_CLASSIFY_SHADOWS : 0u) | RB_RT_MEASURE_ITEMS | (rt.shortenShadowRays ? RB_RT_SHORTEN_SHADOW_RAYS : 0u);
  }

  // Whether selected items are traced at a reduced rate (the policies that select items).
  bool reducedRates() const {
    const Policy p = settings.policy;
    const ItemRate r = settings.rayTracing.rate;
    return r != ItemRate::Full && (p == Policy::Benefit || ((p == Policy::All || p == Policy::Classified) && r != ItemRate::Auto));
  }

  void computeToCompute(VkCommandBuffer cmd) {
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }

  bool native() const { return scene.tracer->kind() == Tracer::Native; }

  // The object records for the moved objects' new transforms (and their culling spheres).
  std::vector<gpu::GpuObject> refreshObjectRecords() {
    std::vector<gpu::GpuObject> objects;
    for (const Object& o : scene.shell.objects) objects.push_back(passes::gpuObject(scene, o));
    for (size_t i = 0; i < objects.size(); ++i) scene.objectSpheres[i] = objects[i].boundsCenterRadius;
    return objects;
  }

  // Points the G-buffer bindings of the slot's sets at `g` when they read other views. The
  // slot's previous frame has completed (its fence, or recordFrame's contract).
  void bindGBuffer(Slot& slot, const core::GBuffer& g) {
    const core::GBuffer& b = slot.gbuffer;
    if (b.depth == g.depth && b.normal == g.normal && b.baseMetal == g.baseMetal && b.roughTransIor == g.roughTransIor &&
        b.emissive == g.emissive && b.objectId == g.objectId && b.materialId == g.materialId && b.position == g.position && b.layout == g.layout)
      return;
    slot.gbuffer = g;
    layouts.writeAll(uint32_t(&slot - slots), [&](VkDescriptorSet set, std::span<const uint32_t> bindings) {
      std::vector<uint32_t> gbufferOnly;
      for (uint32_t x : bindings)
        if (passes::isGBufferBinding(x)) gbufferOnly.push_back(x);
      passes::writeSet(ctx, set, gbufferOnly, slot.uniforms, scene, targets, g, selection.buffers(), samplers);
    });
  }

  void record(Slot& slot, const glm::mat4& viewProj) {
    VkCommandBuffer cmd = slot.cmd;
    VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
    recordCommands(slot, cmd, viewProj, false);
    VK_CHECK(vkEndCommandBuffer(cmd));
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
    selection.beginFrame(s);
    run(Pass::GBuffer, hostGBuffer ? PassSkip::HostGBuffer : PassSkip::None, [&] { gbuffer.record(fc); });
    // The classifier's counts are the items' pixels for `benefit`; otherwise only objectMetrics reads them.
    const bool classify = settings.objectMetrics || (traced && settings.policy == Policy::Benefit);
    const PassSkip nothingTraced = settings.policy == Policy::None ? PassSkip::PolicyTracesNothing : PassSkip::NoEffectInScene;
    run(Pass::Coverage, settings.objectMetrics || traced ? PassSkip::None : nothingTraced,
        [&] { selection.recordCoverage(fc, classify); });
    if (traced) computeToCompute(cmd);
    run(Pass::Select, traced ? PassSkip::None : nothingTraced, [&] { selection.recordSelect(fc, s, settings); });
    // With a budgeted policy unselected objects keep the shadow maps.
    const bool everyPixelTracesShadows = (traced & RB_RT_SHADOWS) && settings.policy == Policy::All;
    run(Pass::ShadowMaps, !shadowMaps ? PassSkip::NoLights : everyPixelTracesShadows ? PassSkip::EveryPixelTracesShadows : PassSkip::None,
        [&] { shadowMaps->record(fc); });
    run(Pass::Environment, environmentReady ? PassSkip::EnvironmentReady : PassSkip::None, [&] { environment.record(fc); });
    environmentReady = true;
    // Items at a reduced ray rate are filled inside the trace passes (shaders/include/tile_fill.glsl).
    run(Pass::TraceShadows, traceSkip(RB_RT_SHADOWS, effects.shadows), [&] { traceShadows.recordOverTiles(fc, reducedRates()); });
    if (traced & RB_RT_SHADOWS) computeToCompute(cmd);
    // The environment fallback first: the lighting pass reads it to measure the display error
    // of the traced shadows (RB_RT_MEASURE_ITEMS).
    timed(Pass::EnvFallback, [&] { envFallback.record(fc); });
    computeToCompute(cmd);
    timed(Pass::Lighting, [&] { lighting.record(fc); });
    const PassSkip effectsSkip = traceSkip(RB_RT_REFLECTIONS | RB_RT_REFRACTIONS, effects.reflections || effects.refractions);
    if (effectsSkip == PassSkip::None) computeToCompute(cmd);
    run(Pass::TraceEffects, effectsSkip, [&] { traceEffects.recordOverTiles(fc, reducedRates()); });
    computeToCompute(cmd);
    timed(Pass::Compose, [&] { compose.record(fc); });
    selection.recordStats(cmd, s);
  }

  std::vector<FrameTiming> render(const Camera& camera) {
    std::vector<FrameTiming> done;
    Slot& slot = slots[frameIndex % kFramesInFlight];
    claimFrames(false);
    if (auto t = retire(slot)) done.push_back(*t);
    bindGBuffer(slot, targets.gbufferViews());
    writeUniforms(slot, camera);
    const float aspect = float(settings.width) / float(settings.height);
    record(slot, camera.projection(aspect) * camera.view());
    VkCommandBuffer cmd = slot.cmd;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    VK_CHECK(vkQueueSubmit(ctx.queue(), 1, &si, slot.fence));
    slot.inFlight = true;
    slot.frame = frameIndex++;
    return done;
  }

  // recordFrame: the slot's previous frame has completed by the host's contract.
  void recordFrame(VkCommandBuffer cmd, const Camera& camera, const core::GBuffer& g) {
    if (!cmd) throw Error("recordFrame: no command buffer");
    for (VkImageView v : {g.depth, g.normal, g.baseMetal, g.roughTransIor, g.emissive, g.objectId, g.materialId, g.position})
      if (!v) throw Error("recordFrame: every G-buffer view must be set (core::GBuffer)");
    if (g.layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL && g.layout != VK_IMAGE_LAYOUT_GENERAL)
      throw Error("recordFrame: the G-buffer's layout must be SHADER_READ_ONLY_OPTIMAL or GENERAL");
    claimFrames(true);
    Slot& slot = slots[frameIndex % kFramesInFlight];
    if (slot.recorded) completed.push_back(collect(slot));
    bindGBuffer(slot, g);
    writeUniforms(slot, camera);
    const float aspect = float(settings.width) / float(settings.height);
    recordCommands(slot, cmd, camera.projection(aspect) * camera.view(), true);
    slot.recorded = true;
    slot.frame = frameIndex++;
  }

  std::vector<FrameTiming> completed;  // recordFrame's frames collected, not yet returned
  std::optional<bool> hostFrames;      // whether the frames are recorded into a host's command buffers

  // A renderer's frames are all its own (render) or all recorded into a host's command
  // buffers (recordFrame): the slots' completion comes from its fences or from the host.
  void claimFrames(bool host) {
    if (!hostFrames) hostFrames = host;
    if (*hostFrames != host)
      throw Error(host ? "recordFrame() after render(): a renderer's frames are either its own or recorded into a host's command buffers"
                       : "render() after recordFrame(): a renderer's frames are either its own or recorded into a host's command buffers");
  }

  // Forgets what the selection learned (S, work per pixel) and switches policy and budget;
  // the time scale learned so far for the new policy's cost unit is kept (the prior if none).
  std::vector<FrameTiming> restartSelection(Policy policy, float budgetMs, BenefitAblation ablation, ItemRate rate) {
    RenderSettings next = settings;
    next.policy = policy;
    next.budgetMs = budgetMs;
    next.benefitAblation = ablation;
    next.rayTracing.rate = rate;
    validateSettings(next);
    std::vector<FrameTiming> done = finish();
    settings = next;
    selection.restart(settings);
    return done;
  }

  void setCostModel(const CostModel& m) {
    for (double v : {m.msPerWorkUnit, m.msPerPaperCost, m.stageOverheadMs, m.traceFixedMs})
      if (!std::isfinite(v) || v < 0.0 || v > 1e6) throw Error("cost model values must be finite and within 0..1e6, got " + std::to_string(v));
    selection.setCostModel(m);
  }

  // Waits for the frames in flight without reading them (teardown).
  void waitForFrames() {
    for (Slot& slot : slots)
      if (slot.inFlight) {
        VkFence fence = slot.fence;
        vkWaitForFences(ctx.device(), 1, &fence, VK_TRUE, UINT64_MAX);  // no throw in a destructor
      }
  }

  std::vector<FrameTiming> finish() {
    std::vector<FrameTiming> done;
    // Oldest first: the slot after the last-used one holds the older frame.
    for (uint32_t k = 0; k < kFramesInFlight; ++k)
      if (auto t = retire(slots[(frameIndex + k) % kFramesInFlight])) done.push_back(*t);
    return done;
  }
};

Renderer::Renderer(const Scene& scene, const RenderSettings& settings) : Renderer(scene, settings, testing::Checks{}) {}

Renderer::Renderer(const Scene& scene, const RenderSettings& settings, const testing::Checks& checks) {
  validateSettings(settings);
  const vk::DescriptorNeeds needs = passes::descriptorNeeds(uint32_t(scene.textures.size()), false);
  impl_ = std::make_unique<Impl>(scene, settings, std::make_unique<vk::Context>(vk::ContextOptions{settings.validation, settings.device, needs}),
                                 checks);
}

Renderer::Renderer(const Scene& scene, const RenderSettings& settings, const core::HostDevice& host) {
  validateSettings(settings);
  if (settings.validation || !settings.device.empty())
    throw Error("RenderSettings::validation and ::device choose the renderer's own device; on a host's device the host's instance decides them");
  impl_ = std::make_unique<Impl>(scene, settings, std::make_unique<vk::Context>(host));
}

Renderer::~Renderer() {
  if (impl_) impl_->waitForFrames();
}

std::vector<FrameTiming> Renderer::render(const Camera& camera) { return impl_->render(camera); }

std::vector<FrameTiming> Renderer::finish() { return impl_->finish(); }

void Renderer::recordFrame(VkCommandBuffer commandBuffer, const Camera& camera, const core::GBuffer& gbuffer) {
  impl_->recordFrame(commandBuffer, camera, gbuffer);
}

std::vector<FrameTiming> Renderer::completedFrames() { return std::exchange(impl_->completed, {}); }

core::FrameOutputs Renderer::outputs() const {
  const passes::FrameTargets& t = impl_->targets;
  return {t.hdr.image, t.ldr.image, t.hdr.view, t.ldr.view, t.direct.image, t.indirect.image, t.direct.view, t.indirect.view, VK_IMAGE_LAYOUT_GENERAL};
}

std::vector<FrameTiming> Renderer::restartSelection(Policy policy, float budgetMs, BenefitAblation ablation, ItemRate rate) {
  return impl_->restartSelection(policy, budgetMs, ablation, rate);
}

CostModel Renderer::costModel() const { return impl_->selection.costModel(); }

void Renderer::setCostModel(const CostModel& model) { impl_->setCostModel(model); }

void Renderer::setObjectTransform(uint32_t objectId, const glm::mat4& transform) {
  raybudget::setObjectTransform(impl_->scene.shell, objectId, transform);
  impl_->objectsMoved = true;
}

std::vector<ObjectMetrics> Renderer::objectMetrics() {
  Impl& r = *impl_;
  if (!r.settings.objectMetrics) throw Error("objectMetrics() needs RenderSettings::objectMetrics");
  if (r.frameIndex == 0) throw Error("objectMetrics() before any frame was rendered");
  return r.selection.objectMetrics();
}

FrameImages Renderer::readback(bool gbufferDetail) {
  Impl& r = *impl_;
  if (r.frameIndex == 0) throw Error("readback() before any frame was rendered");
  // Frames recorded into a host's command buffers read the host's G-buffer: only the
  // outputs are the renderer's.
  const bool hostFrames = r.hostFrames.value_or(false);
  if (hostFrames && gbufferDetail) throw Error("readback(true): the G-buffer of recordFrame's frames is the host's");
  VK_CHECK(vkQueueWaitIdle(r.ctx.queue()));
  const passes::FrameTargets& t = r.targets;
  const VkDeviceSize pixels = VkDeviceSize(t.width) * t.height;
  const uint32_t maskLayers = t.shadowMask.desc.layers;
  struct Source {
    const vk::Image* image;
    VkImageLayout layout;  // the layout the frame keeps it in
    VkDeviceSize bytes;
    uint32_t layers;
  };
  std::vector<Source> sources = {{&t.ldr, VK_IMAGE_LAYOUT_GENERAL, pixels * 4, 1}, {&t.hdr, VK_IMAGE_LAYOUT_GENERAL, pixels * 8, 1}};
  if (!hostFrames) sources.push_back({&t.objectId, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, pixels * 4, 1});
  if (gbufferDetail) {
    sources.push_back({&t.position, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, pixels * 16, 1});
    sources.push_back({&t.shadowMask, VK_IMAGE_LAYOUT_GENERAL, pixels * 4 * maskLayers, maskLayers});
    sources.push_back({&t.normal, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, pixels * 8, 1});
    sources.push_back({&t.roughTransIor, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, pixels * 8, 1});
    sources.push_back({&t.baseMetal, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, pixels * 4, 1});
    sources.push_back({&t.depth, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, pixels * 4, 1});
    sources.push_back({&t.emissive, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, pixels * 8, 1});
    sources.push_back({&t.materialId, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, pixels * 4, 1});
  }
  std::vector<vk::Buffer> buffers;
  for (const Source& src : sources) buffers.push_back(vk::createBuffer(r.ctx, src.bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true));
  r.ctx.submitAndWait([&](VkCommandBuffer cmd) {
    // Each source goes to TRANSFER_SRC for its copy and back to the layout the frame expects.
    for (size_t i = 0; i < sources.size(); ++i) {
      const Source& src = sources[i];
      vk::imageBarrier(cmd, *src.image, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT, src.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
      VkBufferImageCopy copy{};
      copy.imageSubresource = {src.image->aspect, 0, 0, src.layers};
      copy.imageExtent = {t.width, t.height, 1};
      vkCmdCopyImageToBuffer(cmd, src.image->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffers[i].buffer, 1, &copy);
      vk::imageBarrier(cmd, *src.image, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, src.layout);
    }
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  });
  FrameImages out;
  out.width = t.width;
  out.height = t.height;
  auto take = [&](auto& vec, size_t i) {
    vec.resize(size_t(sources[i].bytes) / sizeof(vec[0]));
    std::memcpy(vec.data(), buffers[i].mapped, size_t(sources[i].bytes));
  };
  take(out.ldrRgba8, 0);
  take(out.hdrRgba16, 1);
  if (!hostFrames) take(out.objectIds, 2);
  if (gbufferDetail) {
    take(out.positions, 3);
    take(out.shadowMask, 4);
    take(out.normals, 5);
    take(out.roughTransIor, 6);
    take(out.baseMetal, 7);
    take(out.depth, 8);
    take(out.emissive, 9);
    take(out.materialIds, 10);
  }
  return out;
}

AccelStats Renderer::accelStats() const { return impl_->scene.tracer->stats(); }

SceneEffects Renderer::sceneEffects() const { return impl_->effects; }

std::vector<std::string> Renderer::builtPipelines() const {
  const Impl& r = *impl_;
  std::vector<std::string> out = {"gbuffer", "coverage", "select", "environment", "env_fallback", "lighting", "compose"};
  if (r.shadowMaps) out.push_back("shadow_maps");
  if (r.traceShadows.builtPlain()) out.push_back("trace_shadows");
  if (r.traceShadows.builtFilling()) out.push_back("trace_shadows+fill");
  if (r.traceEffects.builtPlain()) out.push_back("trace_effects");
  if (r.traceEffects.builtFilling()) out.push_back("trace_effects+fill");
  return out;
}

std::string Renderer::deviceName() const { return impl_->ctx.properties().deviceName; }

std::vector<std::string> Renderer::validationMessages() const { return impl_->ctx.validationMessages(); }

float Renderer::aspect() const { return float(impl_->settings.width) / float(impl_->settings.height); }

}  // namespace raybudget
