// The names of policies, passes and rates, the checks on settings, and FrameTiming's sums.
#include "raybudget/settings.h"

#include <cmath>

#include "raybudget/error.h"
#include "select/cost_model.h"
#include "select/policies.h"
#include "select/selection_stage.h"
#include "shared/config.h"

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
    case ItemRate::Sixteenth: return "sixteenth";
    case ItemRate::Auto: return "auto";
    case ItemRate::Full: break;
  }
  return "full";
}

ItemRate parseItemRate(const std::string& name) {
  for (ItemRate r : {ItemRate::Full, ItemRate::Half, ItemRate::Quarter, ItemRate::Sixteenth, ItemRate::Auto})
    if (name == itemRateName(r)) return r;
  throw Error("unknown ray rate '" + name + "' (full, half, quarter, sixteenth, auto)");
}

const char* passSkipText(PassSkip skip) {
  switch (skip) {
    case PassSkip::None: return "";
    case PassSkip::PolicyTracesNothing: return "the policy traces nothing";
    case PassSkip::BudgetBelowFixedCost: return "the budget is at or below the stage's fixed cost: nothing would be traced";
    case PassSkip::FullRate: return "every item is traced at full ray rate: nothing to fill";
    case PassSkip::NoEffectInScene: return "the scene has nothing the switched-on effects could trace";
    case PassSkip::EffectsOff: return "its effects are switched off";
    case PassSkip::NoLights: return "no light (with a shadow map) in the scene";
    case PassSkip::NoSmoothOrTransmissiveMaterial: return "no material smooth enough to reflect or transmissive";
    case PassSkip::EveryPixelTracesShadows: return "every pixel traces its shadows";
    case PassSkip::EnvironmentReady: return "the static environment is built";
    case PassSkip::HostGBuffer: return "the host rasterised the G-buffer";
    case PassSkip::ShadowMapsCurrent: return "the maps are current: no caster in a light's view moved";
    case PassSkip::NoTransmissionInView: return "no transmissive surface in view";
    case PassSkip::EveryPixelTracesRefractions: return "every transmissive pixel traces its refractions";
    case PassSkip::FallbackOff: return "the fallback is switched off";
    case PassSkip::ProbesCurrent: return "the probes are current: nothing inside their boxes moved";
    case PassSkip::NoReflectionProbe: return "no probe: none authored, and the scene has no surroundings to capture (a model, objects with nothing spanning them)";
    case PassSkip::NoPreviousFrame: return "no earlier frame to reflect";
    case PassSkip::EveryPixelTracesReflections: return "every smooth pixel traces its reflection";
    case PassSkip::NoSmoothMaterial: return "no material smooth enough for screen-space reflections";
    case PassSkip::ComposedInLighting: return "no reflection or refraction is traced: the lighting pass composed the frame";
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
    case Pass::Lighting: return "lighting";
    case Pass::Compose: return "compose";
    case Pass::BehindGlass: return "behind_glass";
    case Pass::ReflectionProbes: return "reflection_probes";
    case Pass::ScreenSpaceReflections: return "ssr";
    case Pass::FillEffects: return "fill_effects";
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
  for (Pass p : {Pass::TraceShadows, Pass::TraceEffects, Pass::FillEffects}) ms += this->ms(p);
  return ms;
}

double FrameTiming::rtStageMs() const {
  return ms(Pass::Coverage) + ms(Pass::Select) + traceMs();
}

void validateSettings(const RenderSettings& s) {
  if (s.width == 0 || s.height == 0 || s.width > 16384 || s.height > 16384)
    throw Error("render size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " is outside 1..16384");
  if (s.shadowMapSize < 16 || s.shadowMapSize > 8192) throw Error("shadow map size must be within 16..8192");
  if (!std::isfinite(s.shadowNormalOffset) || s.shadowNormalOffset < 0.0f || s.shadowNormalOffset > 16.0f)
    throw Error("the shadow maps' normal offset (shadowNormalOffset) must be within 0..16 texels, got " + std::to_string(s.shadowNormalOffset));
  if (!std::isfinite(s.shadowSlopeBias) || s.shadowSlopeBias < 0.0f || s.shadowSlopeBias > 16.0f)
    throw Error("the shadow pass's slope-scaled bias (shadowSlopeBias) must be within 0..16, got " + std::to_string(s.shadowSlopeBias));
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
  if (uint32_t(s.rayTracing.rate) > uint32_t(ItemRate::Auto))
    throw Error("the ray rate (rayTracing.rate) must be full, half, quarter, sixteenth or auto, got value " +
                std::to_string(uint32_t(s.rayTracing.rate)));
  if (s.rayTracing.depth < 1 || s.rayTracing.depth > RB_RT_MAX_DEPTH)
    throw Error("ray-tracing depth must be within 1.." + std::to_string(RB_RT_MAX_DEPTH));
}


double priorMsPerWorkUnit(uint32_t width, uint32_t height) { return select::priorMsPerUnit(select::CostUnit::Work, width, height); }

}  // namespace raybudget
