#include "select/selection_stage.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "select/cost_model.h"
#include "select/coverage_pass.h"
#include "select/gpu_selector.h"
#include "select/select_pass.h"
#include "select/stage_deadline.h"
#include "shared/config.h"
#include "vk/check.h"
#include "vk/resources.h"

namespace raybudget::select {

Policy toSelectPolicy(raybudget::Policy policy) {
  switch (policy) {
    case raybudget::Policy::None: return Policy::None;
    case raybudget::Policy::All: return Policy::All;
    case raybudget::Policy::Paper: return Policy::Paper;
    case raybudget::Policy::Density: return Policy::Density;
    case raybudget::Policy::Nearest: return Policy::Nearest;
    case raybudget::Policy::Random: return Policy::Random;
    case raybudget::Policy::Benefit: return Policy::Benefit;
    case raybudget::Policy::Classified: return Policy::All;  // every item (the shadow pass classifies)
  }
  return Policy::None;
}

namespace {

PolicyOptions policyOptions(const RenderSettings& s) {
  const bool segments = s.policy == raybudget::Policy::Benefit && s.rayTracing.rate == ItemRate::Auto;
  return {s.graphPointers, s.seed, 1, 4096, segments, segments};
}

// The effects (RB_RT_* bits) whose reduced rates the temporal fill carries on a still view:
// reflections and refractions (include/fill_history.glsl), and shadows when every light has a
// place in the shadow history (include/shadow_history.glsl).
uint32_t historyEffects(const RenderSettings& s, uint32_t lights) {
  if (!s.rayTracing.temporalFill) return 0u;
  const uint32_t paths = RB_RT_REFLECTIONS | RB_RT_REFRACTIONS;
  return lights <= RB_SHADOW_HISTORY_LIGHTS ? paths | RB_RT_SHADOWS : paths;
}

ItemFrame itemFrame(const RenderSettings& s, uint32_t lights, float probeBudget, uint32_t stillFrames) {
  const RayTracingSettings& rt = s.rayTracing;
  const uint32_t effects = (rt.shadows ? RB_RT_SHADOWS : 0u) | (rt.reflections ? RB_RT_REFLECTIONS : 0u) | (rt.refractions ? RB_RT_REFRACTIONS : 0u);
  uint32_t ablation = 0;
  if (s.benefitAblation == BenefitAblation::NoCentrality) ablation = RB_BENEFIT_WITHOUT_CENTRALITY;
  if (s.benefitAblation == BenefitAblation::NoHysteresis) ablation = RB_BENEFIT_WITHOUT_HYSTERESIS;
  if (s.benefitAblation == BenefitAblation::PriorOnly) ablation = RB_BENEFIT_PRIOR_ONLY;
  if (!s.learnTimeScale) ablation |= RB_ITEM_COSTS_UNTIMED;
  const uint32_t history = historyEffects(s, lights);
  return {effects, lights, s.width * s.height, ablation, probeBudget, rateCode(rt.rate), frameFillQualities(stillFrames, history),
          frameFillStill(stillFrames, history)};
}

// An item's rate (RB_RATE_*) in an object's word of the frame's selection (rates.glsl's itemRate).
uint32_t selectedRate(uint32_t word, uint32_t effect) { return (word >> (RB_RATE_SHIFT + 2 * effect)) & 3u; }

// An item's fill share as the candidate pass left it (its segments: rateSegment).
float itemFill(uint32_t effect, const gpu::GpuItemCost& item) { return fillShare(effect, item.fillPerPixel, item.workPerPixel); }

// Each item's fill qualities this frame (itemFillQuality), from the frame's and its object's
// smoothness in the coverage counts.
std::vector<FillQuality> itemFillQualities(const ItemFrame& frame, const gpu::GpuCoverage* counts, uint32_t objects) {
  std::vector<FillQuality> q(size_t(objects) * RB_ITEMS_PER_OBJECT);
  for (uint32_t i = 0; i < objects; ++i) {
    const float g = fillSmoothness(counts[i].sumYHi.y, counts[i].sumYHi.z, counts[i].sumYHi.w);
    for (uint32_t e = 0; e < RB_ITEMS_PER_OBJECT; ++e) q[i * RB_ITEMS_PER_OBJECT + e] = itemFillQuality(e, frame.qualities, frame.still, g);
  }
  return q;
}

// The IDs of a frame's selection flags: objects, or with `benefit` items (one bit each), or
// with rates chosen per item each selected item's segments up to the one its rate ends on
// (`learned`: the items as the candidate pass left them, whose fill shares and `qualities`
// set their segments).
std::vector<uint32_t> selectedIds(const uint32_t* flags, uint32_t objects, bool items, bool segments, const gpu::GpuItemCost* learned,
                                  std::span<const FillQuality> qualities) {
  std::vector<uint32_t> ids;
  for (uint32_t i = 0; i < objects; ++i)
    for (uint32_t e = 0; e < (items ? RB_ITEMS_PER_OBJECT : 1u); ++e) {
      if (!(items ? (flags[i] >> e) & 1u : flags[i] != 0u)) continue;
      const uint32_t id = items ? i * RB_ITEMS_PER_OBJECT + e : i;
      if (!segments) {
        ids.push_back(id);
        continue;
      }
      const uint32_t rate = selectedRate(flags[i], e);
      uint32_t last = 0;
      const float fill = itemFill(e, learned[id]);
      while (last + 1 < rateSegments(fill, qualities[id]) && rateSegment(last, fill, qualities[id]).rate != rate) ++last;
      for (uint32_t k = 0; k <= last; ++k) ids.push_back(id * RB_SEGMENT_SLOTS + k);
    }
  return ids;
}

void readToTransfer(VkCommandBuffer cmd) {
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT);
}

void copyWhole(VkCommandBuffer cmd, VkBuffer from, const vk::Buffer& to) {
  const VkBufferCopy all{0, 0, to.size};
  vkCmdCopyBuffer(cmd, from, to.buffer, 1, &all);
}

}  // namespace

struct SelectionStage::Impl {
  // What one frame in flight selected with, and host-visible copies of what it produced.
  struct Slot {
    vk::Buffer tileHeader;    // the tile lists' headers: rays traced, tiles in either list
    vk::Buffer result;        // the GPU selection's result (gpu_selector.h)
    vk::Buffer candidates;    // with optimalBound or checkCpu: the candidates
    vk::Buffer selection;     // with checkCpu: the selection flags
    // With checkCpu, for the cost model's CPU reference: per-object costs before and
    // after the select pass, the records and K/Q/I/S it read; for `benefit` the items' state
    // before and after and the coverage counts.
    vk::Buffer costsBefore, costsAfter, records, params, itemsBefore, itemsAfter, coverage;
    bool selected = false;      // the frame ran the select pass
    bool stageSkipped = false;  // the frame left the stage out (skipsStage)
    bool budgeted = false;      // ... with a budgeted policy
    double msPerUnit = 0.0;     // the time scale the frame was selected with
    bool scaleSettled = false;  // and whether it was settled (TimeScale::settled)
    float workPerRay = 0.0f;    // and the work a ray costs, for what was never traced
    double traceFixedMs = 0.0;  // ... the trace passes' fixed cost it assumed
    ItemFrame items;  // ... and what `benefit` knew of the frame
    float traceBudgetMs = 0.0f;  // ... and the part of T it left for the work
    float selectBudgetMs = 0.0f;  // ... of which the selection's (the rest: `benefit`'s probe)
    bool belowFixedCost = false;  // T at or below the stage's fixed cost: nothing traced
    bool coverageReused = false;  // the coverage pass kept the frame before's counts (CoveragePass::record)
    double deadlineReserveMs = 0.0;  // the deadline's reserve (StageDeadline::reserveMs)
    bool underDeadline = false;      // ... and whether the trace passes had deadlines
  };

  const vk::Context& ctx;
  std::vector<gpu::GpuObjectParams> initialParams;  // K/Q/I as the selection starts (and restarts)
  uint32_t lights = 0;
  SelectionBuffers buffers;
  CoveragePass coverage;
  SelectPass selectPass;
  // The GPU selection, built for the first budgeted policy (it needs subgroup shuffle and
  // float64, which `none` and `all` never use).
  std::unique_ptr<GpuSelector> selector;
  TimeScale timeScale;
  StageDeadline deadline;
  std::vector<Slot> slots;
  bool checkCpu = false;  // compare every frame with the CPU references (tests)

  Impl(const vk::Context& c, passes::PassLayouts& layouts, const Scene& scene, const RenderSettings& s, uint32_t framesInFlight, bool check)
      : ctx(c),
        initialParams(initialObjectParams(scene, s.rayTracing.maxRoughness)),
        lights(uint32_t(scene.lights.size())),
        buffers(createSelectionBuffers(c, uint32_t(scene.objects.size()), initialParams, s.width, s.height)),
        coverage(c, layouts),
        selectPass(c, layouts),
        timeScale(s.width, s.height),
        slots(framesInFlight),
        checkCpu(check) {
    ensureSelector(s);
    const VkDeviceSize records = std::max<VkDeviceSize>(1, buffers.objects);
    for (Slot& slot : slots) {
      slot.tileHeader = vk::createBuffer(c, kTileListHeaderBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
      slot.result = vk::createBuffer(c, GpuSelector::kResultBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
      if (s.optimalBound || checkCpu)
        // Up to three rate segments per item (`benefit` with rates chosen per item).
        slot.candidates = vk::createBuffer(c, records * RB_ITEMS_PER_OBJECT * 3 * sizeof(gpu::GpuCandidate), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
      if (checkCpu) {
        slot.selection = vk::createBuffer(c, records * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        slot.costsBefore = vk::createBuffer(c, records * sizeof(gpu::GpuObjectCost), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        slot.costsAfter = vk::createBuffer(c, records * sizeof(gpu::GpuObjectCost), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        slot.records = vk::createBuffer(c, records * sizeof(gpu::GpuObjectRecord), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        slot.params = vk::createBuffer(c, records * sizeof(gpu::GpuObjectParams), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        const VkDeviceSize items = (records * RB_ITEMS_PER_OBJECT + 1) * sizeof(gpu::GpuItemCost);
        slot.itemsBefore = vk::createBuffer(c, items, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        slot.itemsAfter = vk::createBuffer(c, items, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        slot.coverage = vk::createBuffer(c, records * sizeof(gpu::GpuCoverage), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
      }
    }
  }

  void ensureSelector(const RenderSettings& s) {
    if (selector || !isBudgeted(s.policy)) return;
    // Room for `benefit`'s items, whichever budgeted policy comes first (restartSelection).
    // `benefit` with rates: up to RB_SEGMENT_SLOTS candidate IDs per item.
    selector = std::make_unique<GpuSelector>(ctx, std::max<uint32_t>(1, buffers.objects) * RB_ITEMS_PER_OBJECT * RB_SEGMENT_SLOTS);
    selector->bindFrame({buffers.objectRecords.buffer, buffers.selection.buffer, buffers.objectParams.buffer, buffers.objectCosts.buffer,
                         buffers.coverage.buffer, buffers.itemCosts.buffer});
  }

  // The trace passes' deadlines (effects, shadows, fill; 0: none) for the frame.
  glm::uvec3 deadlineTicksFor(const RenderSettings& s) const {
    if (!isBudgeted(s.policy) || !s.learnTimeScale || !s.stageDeadline) return glm::uvec3(0u);
    return {deadline.effectsTicks(s.budgetMs), deadline.shadowTicks(s.budgetMs), deadline.fillTicks(s.budgetMs)};
  }

  // T at or below the stage's learned fixed cost: nothing can be traced.
  bool belowFixedCost(const RenderSettings& s, bool coverageReused) const {
    return double(s.budgetMs) <= timeScale.fixedMs(coverageReused);
  }

  void recordSelect(const passes::FrameContext& fc, Slot& slot, const RenderSettings& s, uint32_t stillFrames, bool coverageReused) {
    const VkCommandBuffer cmd = fc.cmd;
    const Policy policy = toSelectPolicy(s.policy);
    slot.selected = true;
    slot.budgeted = isBudgeted(s.policy);
    slot.msPerUnit = timeScale.msPerUnit(costUnitOf(policy));
    slot.scaleSettled = timeScale.settled(costUnitOf(policy));
    slot.workPerRay = float(timeScale.priorWorkPerRay(costUnitOf(policy)));
    slot.traceFixedMs = timeScale.traceFixedMs();
    slot.coverageReused = coverageReused;
    slot.belowFixedCost = belowFixedCost(s, coverageReused);
    slot.deadlineReserveMs = deadline.reserveMs(s.budgetMs);
    slot.underDeadline = deadlineTicksFor(s).x != 0u;
    // Room for the prediction's recent errors (cost_model.h's headroom).
    slot.traceBudgetMs = slot.belowFixedCost ? 0.0f : float((double(s.budgetMs) - timeScale.fixedMs(coverageReused)) / timeScale.headroom(s.budgetConfidence));
    // `benefit` keeps a share of the trace budget for the probe of what it leaves out.
    const bool probe = policy == Policy::Benefit && s.benefitAblation != BenefitAblation::NoProbe;
    const float probeBudgetMs = probe ? slot.traceBudgetMs * s.probeShare : 0.0f;
    slot.selectBudgetMs = slot.traceBudgetMs - probeBudgetMs;
    slot.items = itemFrame(s, lights, probeBudgetMs, stillFrames);
    if (slot.budgeted) {
      const bool check = checkCpu;
      if (check) {  // what the cost model starts from
        readToTransfer(cmd);
        copyWhole(cmd, buffers.objectCosts.buffer, slot.costsBefore);
        copyWhole(cmd, buffers.objectRecords.buffer, slot.records);
        copyWhole(cmd, buffers.objectParams.buffer, slot.params);
        copyWhole(cmd, buffers.itemCosts.buffer, slot.itemsBefore);
        copyWhole(cmd, buffers.coverage.buffer, slot.coverage);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
      }
      selector->recordFrame(cmd, buffers.objects, policy, slot.selectBudgetMs, {float(slot.msPerUnit), slot.workPerRay}, policyOptions(s), slot.items);
      readToTransfer(cmd);
      const VkBufferCopy result{0, 0, GpuSelector::kResultBytes};
      vkCmdCopyBuffer(cmd, selector->resultBuffer(), slot.result.buffer, 1, &result);
      if (s.optimalBound || check) copyWhole(cmd, selector->candidateBuffer(), slot.candidates);
      if (check) {
        copyWhole(cmd, buffers.selection.buffer, slot.selection);
        copyWhole(cmd, buffers.objectCosts.buffer, slot.costsAfter);
        copyWhole(cmd, buffers.itemCosts.buffer, slot.itemsAfter);
      }
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }
    // The unbudgeted policies trace at the setting's rate; auto is `benefit`'s choice.
    const uint32_t fixedRate = s.rayTracing.rate == ItemRate::Auto ? RB_RATE_FULL : rateCode(s.rayTracing.rate);
    selectPass.record(fc, slot.budgeted ? SelectMode::Keep : SelectMode::All, fixedRate);
  }

  // Whether the GPU's per-object cost model (select_candidates.comp, select_apply.comp)
  // equals its CPU reference (cost_model.h) on this frame: each object's learned work per
  // pixel, its restarted counters, and each candidate's predicted cost, bit for bit.
  bool costsMatchCpu(const Slot& slot, Policy policy, std::span<const gpu::GpuCandidate> candidates) const {
    const auto* before = static_cast<const gpu::GpuObjectCost*>(slot.costsBefore.mapped);
    const auto* after = static_cast<const gpu::GpuObjectCost*>(slot.costsAfter.mapped);
    const auto* records = static_cast<const gpu::GpuObjectRecord*>(slot.records.mapped);
    const auto* params = static_cast<const gpu::GpuObjectParams*>(slot.params.mapped);
    const auto* selected = static_cast<const uint32_t*>(slot.selection.mapped);
    std::vector<float> perPixel(buffers.objects);
    for (uint32_t i = 0; i < buffers.objects; ++i) {
      perPixel[i] = learnedWorkPerPixel(before[i].workPerPixel, before[i].work, before[i].pixels);
      // The counters restart; a selected object's pixels are what the trace passes will cover.
      const uint32_t pixels = (selected[i] & RB_ITEMS_ALL) ? std::bit_cast<uint32_t>(records[i].crCandidatePixels.w) : 0u;
      if (std::bit_cast<uint32_t>(perPixel[i]) != std::bit_cast<uint32_t>(after[i].workPerPixel) || after[i].work != 0 || after[i].pixels != pixels)
        return false;
    }
    if (policy == Policy::Benefit) return itemsMatchCpu(slot, candidates);
    size_t expected = 0;
    for (uint32_t i = 0; i < buffers.objects; ++i) expected += records[i].crCandidatePixels.z > 0.5f ? 1 : 0;
    if (expected != candidates.size()) return false;
    double prior = 0.0;
    for (const gpu::GpuCandidate& c : candidates) {
      if (c.id >= buffers.objects || records[c.id].crCandidatePixels.z < 0.5f) return false;
      const gpu::GpuObjectRecord& r = records[c.id];
      const float work = predictedWork(policy, r.crCandidatePixels.x, std::bit_cast<uint32_t>(r.crCandidatePixels.w), perPixel[c.id], params[c.id].kqiS.y, slot.workPerRay);
      if (std::bit_cast<uint32_t>(predictedCost(float(slot.msPerUnit), work)) != std::bit_cast<uint32_t>(c.cost)) return false;
      // `paper`'s cost is its C, never priced by the prior.
      if (policy != Policy::Paper && (selected[c.id] & RB_ITEMS_ALL) && perPixel[c.id] == 0.0f) prior += c.cost;
    }
    return priorCostMatches(slot, prior);
  }

  // Whether the partial item the walk kept in the items' totals record (shared/selection.h) is
  // the CPU's: the item and its share of tiles, bit for bit.
  bool partialMatches(const Slot& slot, const PartialItem& partial) const {
    const gpu::GpuItemCost& totals = static_cast<const gpu::GpuItemCost*>(slot.itemsAfter.mapped)[buffers.objects * RB_ITEMS_PER_OBJECT];
    const uint32_t item = partial.id == UINT32_MAX ? 0u : partial.id / RB_SEGMENT_SLOTS + 1u;
    return totals.selectedLast == item && std::bit_cast<uint32_t>(totals.benefit) == std::bit_cast<uint32_t>(partial.share);
  }

  // Whether the walk's cost of the selected candidates priced by the prior (result word 9,
  // select_walk.comp's priorPricedCost) equals the CPU's sum, summed in another order on the
  // GPU: within a relative 1e-5.
  static bool priorCostMatches(const Slot& slot, double cpu) {
    const double gpu = std::bit_cast<float>(static_cast<const uint32_t*>(slot.result.mapped)[9]);
    return std::abs(gpu - cpu) <= 1e-5 * cpu;
  }

  // `benefit`: whether each item's learned state (cost_model.h's learnItem), restarted
  // counters, S, traced pixels and ray rate, and each item candidate's cost and value equal the CPU
  // reference bit for bit; and whether the probe marks exactly the candidates left out, at
  // the stride probeStride gives for their cost (summed in another order on the GPU: within
  // a relative 1e-5).
  bool itemsMatchCpu(const Slot& slot, std::span<const gpu::GpuCandidate> candidates) const {
    const auto* before = static_cast<const gpu::GpuItemCost*>(slot.itemsBefore.mapped);
    const auto* after = static_cast<const gpu::GpuItemCost*>(slot.itemsAfter.mapped);
    const auto* records = static_cast<const gpu::GpuObjectRecord*>(slot.records.mapped);
    const auto* params = static_cast<const gpu::GpuObjectParams*>(slot.params.mapped);
    const auto* counts = static_cast<const gpu::GpuCoverage*>(slot.coverage.mapped);
    const auto* selected = static_cast<const uint32_t*>(slot.selection.mapped);
    const ItemFrame frame = slot.items;
    auto pixelsOf = [&](uint32_t i, uint32_t e) -> uint32_t {
      if (!(frame.effects & (1u << e))) return 0;
      if (e == RB_ITEM_SHADOWS) return frame.lights > 0 ? std::bit_cast<uint32_t>(records[i].crCandidatePixels.w) : 0u;
      return e == RB_ITEM_REFLECTIONS ? counts[i].sumYHi.y : counts[i].sumYHi.z;
    };
    const uint32_t items = buffers.objects * RB_ITEMS_PER_OBJECT;
    // With rates chosen per item the candidates are the items' rate segments.
    const bool segments = frame.rate == RB_RATE_AUTO;
    auto itemOf = [&](uint32_t id) { return segments ? id / RB_SEGMENT_SLOTS : id; };
    double left = 0.0, prior = 0.0;
    // The candidates taken (items, or their rate segments), in ascending order.
    const std::vector<FillQuality> qualities = itemFillQualities(frame, counts, buffers.objects);
    const std::vector<uint32_t> taken = selectedIds(selected, buffers.objects, true, segments, after, qualities);
    for (const gpu::GpuCandidate& c : candidates) {
      const uint32_t item = itemOf(c.id);
      if (item < items && !((selected[item / RB_ITEMS_PER_OBJECT] >> (item % RB_ITEMS_PER_OBJECT)) & 1u)) left += c.cost;
    }
    const uint32_t stride = after[items].pixels;
    if (!probeStrideFits(stride, left, frame.probeBudget, 1e-5)) return false;
    std::vector<ItemLearned> learned(items);
    std::vector<float> fill(items);  // each item's fill share, which prices its rates
    size_t expected = 0;
    for (uint32_t id = 0; id < items; ++id) {
      const uint32_t i = id / RB_ITEMS_PER_OBJECT, e = id % RB_ITEMS_PER_OBJECT;
      const gpu::GpuItemCost& b = before[id];
      learned[id] = learnItem(params[i].priors[int(e)], {b.workPerPixel, b.benefit, b.measured != 0, b.fillPerPixel},
                              {b.work, b.ticks, b.error, b.pixels, b.selectedLast == 0, b.selectedLast == 0 ? RB_RATE_FULL : b.selectedLast - 1,
                               b.skippedTicks, b.skippedPixels},
                              frame.ablation & RB_ITEM_COSTS_UNTIMED ? 0.0f : float(RB_WORK_PER_CLOCK_UNIT), frame.ablation,
                              priorItemWorkPerPixel(e, frame.lights, slot.workPerRay));
      fill[id] = fillShare(e, learned[id].fillPerPixel, learned[id].workPerPixel);
      const gpu::GpuItemCost& a = after[id];
      const bool on = (selected[i] >> e) & 1u;
      // The rate: the setting's, or the walk's choice (which selectionMatchesCpu checks).
      const uint32_t rate = selectedRate(selected[i], e);
      if (std::bit_cast<uint32_t>(a.workPerPixel) != std::bit_cast<uint32_t>(learned[id].workPerPixel) ||
          std::bit_cast<uint32_t>(a.benefit) != std::bit_cast<uint32_t>(learned[id].benefit) || (a.measured != 0) != learned[id].measured ||
          std::bit_cast<uint32_t>(a.fillPerPixel) != std::bit_cast<uint32_t>(learned[id].fillPerPixel) || a.skippedTicks != 0 ||
          a.skippedPixels != 0 || a.work != 0 || a.ticks != 0 || a.error != 0 || a.selectedLast != (on ? 1u + rate : 0u) ||
          a.pixels != (on && rate == RB_RATE_FULL ? pixelsOf(i, e) : 0u))
        return false;
      if (!segments && rate != (on ? frame.rate : 0u)) return false;
      if (!on && rate != 0u) return false;
      const bool candidate = records[i].crCandidatePixels.z > 0.5f && pixelsOf(i, e) > 0;
      if (candidate) expected += segments ? rateSegments(fill[id], qualities[id]) : 1u;
      const bool probed = stride != 0 && candidate && !on;  // the probe marks what the walk left out
      if (((selected[i] >> (RB_PROBE_SHIFT + e)) & 1u) != (probed ? 1u : 0u)) return false;
    }
    if (expected != candidates.size()) return false;
    for (const gpu::GpuCandidate& c : candidates) {
      const uint32_t item = itemOf(c.id);
      if (item >= items) return false;
      const uint32_t i = item / RB_ITEMS_PER_OBJECT, e = item % RB_ITEMS_PER_OBJECT, pixels = pixelsOf(i, e);
      if (records[i].crCandidatePixels.z < 0.5f || pixels == 0) return false;
      const float work = predictedItemWork(e, pixels, learned[item].workPerPixel, frame.lights, slot.workPerRay) * rateShare(frame.rate, fill[item]);
      const glm::vec4 kqiS = params[i].kqiS;
      float cost = predictedCost(float(slot.msPerUnit), work);
      float value = itemValue(pixels, frame.pixels, records[i].apdv.y, learned[item].benefit, before[item].selectedLast != 0, kqiS.x, kqiS.z, frame.ablation);
      if (segments) {
        const uint32_t k = c.id % RB_SEGMENT_SLOTS;
        if (k >= rateSegments(fill[item], qualities[item])) return false;
        const RateSegment s = rateSegment(k, fill[item], qualities[item]);
        cost *= s.costShare;
        value *= s.valueShare;
      }
      if (std::bit_cast<uint32_t>(cost) != std::bit_cast<uint32_t>(c.cost) || std::bit_cast<uint32_t>(value) != std::bit_cast<uint32_t>(c.value))
        return false;
      if (std::binary_search(taken.begin(), taken.end(), c.id) && learned[item].workPerPixel == 0.0f) prior += c.cost;
    }
    return priorCostMatches(slot, prior);
  }

  void retire(Slot& slot, const RenderSettings& s, FrameTiming& t) {
    const auto* header = static_cast<const uint32_t*>(slot.tileHeader.mapped);
    t.tracedTiles = slot.selected ? header[7] : 0u;
    t.shadowTiles = slot.selected ? header[16] : 0u;
    t.effectTiles = slot.selected ? header[17] : 0u;
    t.shadowChunks = slot.selected ? header[9] : 0u;
    t.effectChunks = slot.selected ? header[10] : 0u;
    t.fillChunks = slot.selected ? header[11] : 0u;
    t.raysTraced = slot.selected ? header[3] : 0u;
    t.deadlineCutPixels = slot.selected ? header[24] : 0u;
    t.fillCutPixels = slot.selected ? header[27] : 0u;
    if (slot.selected) {
      // The device clock's rate: its span from coverage's start to the shadow pass's end (the
      // select pass's without one) against the same passes' timestamps (stage_deadline.h).
      if (header[20] != 0u) deadline.learn(header[21], t.ms(Pass::Coverage) + t.ms(Pass::Select) + t.ms(Pass::TraceShadows));
      deadline.learnFrame({.budgetMs = s.budgetMs,
                           .reserveMs = slot.deadlineReserveMs,
                           .stageMs = t.rtStageMs(),
                           .effectsMs = t.ms(Pass::TraceEffects),
                           .fillMs = t.ms(Pass::FillEffects),
                           .cut = t.deadlineCutPixels > 0,
                           .effectsCut = t.deadlineCutPixels != header[26],
                           .fillCut = t.fillCutPixels > 0,
                           .underDeadline = slot.underDeadline});
    }
    if (slot.stageSkipped) {
      t.budgetMs = s.budgetMs;
      t.budgetBelowFixedCost = true;
      return;
    }
    if (!slot.selected || !slot.budgeted) return;
    const Policy policy = toSelectPolicy(s.policy);
    const auto* r = static_cast<const uint32_t*>(slot.result.mapped);
    t.budgetMs = s.budgetMs;
    t.traceBudgetMs = slot.traceBudgetMs;
    const double predictedWorkMs = std::bit_cast<float>(r[1]);
    t.predictedTraceMs = slot.traceFixedMs + predictedWorkMs;
    t.budgetBelowFixedCost = slot.belowFixedCost;
    t.selectedValue = std::bit_cast<float>(r[2]);
    t.selectedObjects = r[3];
    t.selectionChanges = r[4];
    t.itemOptionChanges = r[8];
    t.partialShare = std::bit_cast<float>(r[10]);
    t.selectionSorted = r[7] != 0;
    if (s.optimalBound || checkCpu) {
      const std::span<const gpu::GpuCandidate> g(static_cast<const gpu::GpuCandidate*>(slot.candidates.mapped), r[0]);
      std::vector<Candidate> c;
      for (const gpu::GpuCandidate& x : g) c.push_back({x.id, x.cost, x.value, x.distance});
      if (s.optimalBound) {
        t.optimalValueBound = optimalValueBound(c, slot.selectBudgetMs, 4096, slot.items.rate == RB_RATE_AUTO);
        if (!c.empty())
          t.cheapestCandidateMs = std::min_element(c.begin(), c.end(), [](const auto& a, const auto& b) { return a.cost < b.cost; })->cost;
        for (const Candidate& x : c) t.candidatesMs += x.cost;
      }
      if (checkCpu) {
        const auto* flags = static_cast<const uint32_t*>(slot.selection.mapped);
        const std::vector<uint32_t> gpuIds =
            selectedIds(flags, buffers.objects, policy == Policy::Benefit, slot.items.rate == RB_RATE_AUTO,
                        static_cast<const gpu::GpuItemCost*>(slot.itemsAfter.mapped),
                        itemFillQualities(slot.items, static_cast<const gpu::GpuCoverage*>(slot.coverage.mapped), buffers.objects));
        const Selection cpu = selectObjects(policy, c, slot.selectBudgetMs, policyOptions(s));
        t.selectionMatchesCpu = gpuIds == cpu.ids && (policy != Policy::Benefit || partialMatches(slot, cpu.partial));
        t.costsMatchCpu = costsMatchCpu(slot, policy, g);
      }
    }
    t.measuredTraceMs = t.traceMs();
    if (!s.learnTimeScale) return;
    double predictedWork = predictedWorkMs / slot.msPerUnit;
    // The deadline cut the frame short: what the items traced was predicted at the selection's
    // work less the cut pixels' (include/deadline_cut.glsl). The object policies predict no work
    // per pixel: their cut frames bound the scale from below (StageMeasurement::cutShort).
    const bool cut = t.deadlineCutPixels > 0, cutShort = cut && policy != Policy::Benefit;
    if (cut && !cutShort) {
      predictedWork -= double(header[25]) / RB_CUT_WORK_UNITS;
      if (predictedWork <= 0.0) return;
    }
    timeScale.learn(costUnitOf(policy), {slot.msPerUnit, predictedWork, t.measuredTraceMs, t.rtStageMs() - t.measuredTraceMs,
                                         r[0] > 0 && r[3] == 0 && !slot.belowFixedCost, slot.selectBudgetMs, t.raysTraced,
                                         double(std::bit_cast<float>(r[9])) / slot.msPerUnit, slot.scaleSettled,
                                         uint64_t(header[8]), cutShort, slot.coverageReused});  // the items' prior's rays (tile list header)
  }

  std::vector<uint32_t> changedParams;  // objects whose K, Q, I the next frame uploads
  uint32_t skippedInRow = 0;            // frames in a row that left the stage out (skipsStage)

  // K, Q and I (not S, which the GPU keeps in kqiS.w) of the changed objects.
  void uploadChangedParams(VkCommandBuffer cmd) {
    if (changedParams.empty()) return;
    for (uint32_t i : changedParams)
      vkCmdUpdateBuffer(cmd, buffers.objectParams.buffer, i * sizeof(gpu::GpuObjectParams), 3 * sizeof(float), &initialParams[i].kqiS);
    changedParams.clear();
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_MEMORY_READ_BIT);
  }

  void restart(const RenderSettings& s) {
    ensureSelector(s);
    timeScale.forgetErrors();
    deadline.restart();
    ctx.submitAndWait([&](VkCommandBuffer cmd) { recordSelectionReset(cmd, buffers, initialParams); });
  }

  std::vector<ObjectMetrics> objectMetrics() const {
    VK_CHECK(vkQueueWaitIdle(ctx.queue()));
    const VkDeviceSize count = buffers.objects, bytes = std::max<VkDeviceSize>(1, count) * sizeof(gpu::GpuObjectRecord);
    const VkDeviceSize flagBytes = std::max<VkDeviceSize>(1, count) * 4, coverageBytes = std::max<VkDeviceSize>(1, count) * sizeof(gpu::GpuCoverage);
    const VkDeviceSize itemBytes = (std::max<VkDeviceSize>(1, count) * RB_ITEMS_PER_OBJECT + 1) * sizeof(gpu::GpuItemCost);
    vk::Buffer host = vk::createBuffer(ctx, bytes + flagBytes + coverageBytes + itemBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                        VK_ACCESS_2_TRANSFER_READ_BIT);
      const VkBufferCopy copy{0, 0, bytes}, flags{0, bytes, flagBytes}, coverageCopy{0, bytes + flagBytes, coverageBytes};
      vkCmdCopyBuffer(cmd, buffers.objectRecords.buffer, host.buffer, 1, &copy);
      vkCmdCopyBuffer(cmd, buffers.selection.buffer, host.buffer, 1, &flags);
      vkCmdCopyBuffer(cmd, buffers.coverage.buffer, host.buffer, 1, &coverageCopy);
      const VkBufferCopy itemCopy{0, bytes + flagBytes + coverageBytes, itemBytes};
      vkCmdCopyBuffer(cmd, buffers.itemCosts.buffer, host.buffer, 1, &itemCopy);
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    const auto* records = static_cast<const gpu::GpuObjectRecord*>(host.mapped);
    const auto* selected = reinterpret_cast<const uint32_t*>(static_cast<const char*>(host.mapped) + bytes);
    const auto* cov = reinterpret_cast<const gpu::GpuCoverage*>(static_cast<const char*>(host.mapped) + bytes + flagBytes);
    const auto* items = reinterpret_cast<const gpu::GpuItemCost*>(static_cast<const char*>(host.mapped) + bytes + flagBytes + coverageBytes);
    std::vector<ObjectMetrics> out(count);
    // The partial item (shared/selection.h), kept in the items' totals record.
    const gpu::GpuItemCost& totals = items[count * RB_ITEMS_PER_OBJECT];
    for (size_t i = 0; i < count; ++i) {
      const gpu::GpuObjectRecord& g = records[i];
      out[i] = {std::bit_cast<uint32_t>(g.crCandidatePixels.w), cov[i].sumYHi.y, cov[i].sumYHi.z, g.apdv.x, g.apdv.y, g.apdv.z, g.apdv.w,
                g.crCandidatePixels.x, g.crCandidatePixels.y, g.crCandidatePixels.z > 0.5f, (selected[i] & RB_ITEMS_ALL) != 0u};
      out[i].selectedItems = selected[i] & RB_ITEMS_ALL;
      out[i].detailedPixels = cov[i].sumYHi.w;
      for (uint32_t e = 0; e < RB_ITEMS_PER_OBJECT; ++e) {
        const uint32_t rate = selectedRate(selected[i], e);
        out[i].itemRate[e] = itemRateOfCode(rate);
      }
      for (uint32_t e = 0; e < RB_ITEMS_PER_OBJECT; ++e) {
        const gpu::GpuItemCost& item = items[i * RB_ITEMS_PER_OBJECT + e];
        out[i].itemError[e] = float(double(item.error) / RB_ERROR_UNITS);
        out[i].itemWork[e] = item.work;
        out[i].itemTicks[e] = uint64_t(item.ticks) * RB_CLOCK_UNIT;
        out[i].itemBenefit[e] = item.benefit;
        out[i].itemCostPerPixel[e] = item.workPerPixel;
        out[i].itemFillPerPixel[e] = item.fillPerPixel;
        out[i].itemTracedPixels[e] = item.pixels;
        out[i].itemSkippedPixels[e] = item.skippedPixels;
        out[i].itemSkippedTicks[e] = uint64_t(item.skippedTicks) * RB_CLOCK_UNIT;
        if (totals.selectedLast == i * RB_ITEMS_PER_OBJECT + e + 1 && ((selected[i] >> e) & 1u)) out[i].itemTileShare[e] = totals.benefit;
      }
    }
    return out;
  }
};

SelectionStage::SelectionStage(const vk::Context& ctx, passes::PassLayouts& layouts, const Scene& scene, const RenderSettings& settings,
                               uint32_t framesInFlight, bool checkAgainstCpu)
    : impl_(std::make_unique<Impl>(ctx, layouts, scene, settings, framesInFlight, checkAgainstCpu)) {}
SelectionStage::~SelectionStage() = default;

const SelectionBuffers& SelectionStage::buffers() const { return impl_->buffers; }

void SelectionStage::beginFrame(VkCommandBuffer cmd, uint32_t slot) {
  impl_->slots[slot].selected = false;
  impl_->slots[slot].budgeted = false;
  impl_->uploadChangedParams(cmd);
}

bool SelectionStage::skipsStage(uint32_t slot, const RenderSettings& settings) {
  Impl& m = *impl_;
  // Below the least fixed cost (a still view's, where one was seen): nothing could be bought.
  const bool below = isBudgeted(settings.policy) && m.timeScale.fixedCostObservations() >= 3 && m.belowFixedCost(settings, true);
  m.skippedInRow = below && m.skippedInRow + 1 < kRemeasureEvery ? m.skippedInRow + 1 : 0;
  m.slots[slot].stageSkipped = m.skippedInRow > 0;
  return m.slots[slot].stageSkipped;
}

void SelectionStage::setObjectParams(uint32_t object, float K, float Q, float I) {
  gpu::GpuObjectParams& p = impl_->initialParams.at(object);
  p.kqiS = glm::vec4(K, Q, I, p.kqiS.w);
  impl_->changedParams.push_back(object);
}

void SelectionStage::recordCoverage(const passes::FrameContext& fc, bool classify, bool reuse) const {
  impl_->coverage.record(fc, classify, reuse);
}

void SelectionStage::recordSelect(const passes::FrameContext& fc, uint32_t slot, const RenderSettings& settings, uint32_t stillFrames,
                                  bool coverageReused) {
  impl_->recordSelect(fc, impl_->slots[slot], settings, stillFrames, coverageReused);
}

glm::uvec3 SelectionStage::deadlineTicks(const RenderSettings& s) const { return impl_->deadlineTicksFor(s); }

void SelectionStage::recordStats(VkCommandBuffer cmd, uint32_t slot) const {
  if (!impl_->slots[slot].selected) return;
  readToTransfer(cmd);
  const VkBufferCopy header{0, 0, kTileListHeaderBytes};
  vkCmdCopyBuffer(cmd, impl_->buffers.tileList.buffer, impl_->slots[slot].tileHeader.buffer, 1, &header);
}

void SelectionStage::retire(uint32_t slot, const RenderSettings& settings, FrameTiming& t) { impl_->retire(impl_->slots[slot], settings, t); }

void SelectionStage::restart(const RenderSettings& settings) { impl_->restart(settings); }

CostModel SelectionStage::costModel() const { return impl_->timeScale.saved(); }

void SelectionStage::setCostModel(const CostModel& m) { impl_->timeScale.set(m); }

std::vector<ObjectMetrics> SelectionStage::objectMetrics() const { return impl_->objectMetrics(); }

}  // namespace raybudget::select
