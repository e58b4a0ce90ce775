#version 460
#extension GL_GOOGLE_include_directive : require
// Frame mode: first each object's learned work per pixel takes in what the trace passes
// counted for it last frame (when it was traced; the native tracer counts nothing, so its
// objects keep the prior), and the counter restarts. Then every candidate object (visible,
// something to trace, R > 0) becomes a selection candidate with its predicted cost, kappa
// times its work: the paper's C for `paper`; for the other policies its pixels times its
// work per pixel (Q times the work a ray costs until measured). `benefit` makes each item of a
// candidate object with pixels to trace a candidate instead, and each item first learns its
// work per pixel and its benefit (below).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "shared/config.h"
#include "include/select_common.glsl"

layout(local_size_x = RB_GROUP_SIZE) in;

// Appends a candidate and adds its cost to the candidates' total for allCandidatesFit
// (select_common.glsl): in units of 2^-20 budget rounded up, one candidate at most 2^21
// (anything above one budget fails anyway), summed per subgroup, then into 64 bits (lo, hi)
// with an explicit carry. Keeps the largest cost and value (result4.xy: a non-negative
// float's bits order as the float), the scales of the walk's sums in no order
// (include/order_free_sum.glsl). Every lane calls it (those with nothing to add with add = false).
void append(bool add, uint id, float cost, float value, float distance) {
  uint units = 0u;
  if (add) {
    uint slot = atomicAdd(result.x, 1u);
    candidates[slot] = GpuCandidate(id, cost, value, distance);
    slotOf[id] = slot;
    float u = ceil(cost / push.budget.x * 1048576.0);
    units = u <= 2097152.0 ? uint(u) : 2097152u;  // NaN compares false: the cap
  }
  uint sum = subgroupAdd(units);
  uvec2 top = subgroupMax(add ? uvec2(floatBitsToUint(cost), floatBitsToUint(value)) & 0x7FFFFFFFu : uvec2(0u));
  if (subgroupElect()) {
    uint old = atomicAdd(result2.y, sum);
    if (old + sum < old) atomicAdd(result2.z, 1u);
    // (A plain read first: after the first few subgroups hardly any has a larger one, and
    // atomics on one word queue up. A stale read costs only an atomic.)
    if (top.x > result4.x) atomicMax(result4.x, top.x);
    if (top.y > result4.y) atomicMax(result4.y, top.y);
  }
}

// engine/src/select/cost_model.cpp is the CPU reference of these lines, equal bit for bit.
// A learned per-pixel figure after an observation: the mean of the two, or the observation
// alone when nothing was learned yet (0).
float averagedWith(float previous, float observed) { return previous > 0.0 ? 0.5 * (previous + observed) : observed; }

// An item left out last frame was traced on the probe's few tiles alone, a sample of one to a
// few 8x8 tiles that is often of its edge or its sky-facing part (NormalTangentMirrorTest's
// shadows: 1.0 units per pixel on a probe's tile against 4.1 over the item, which priced the
// whole object at a sixth of its time): the estimate, or the prior before one, moves towards
// it by a power-of-two share that grows with the pixels probed (an exact product: a fused
// multiply-add rounds alike).
float probedWorkPerPixel(float previous, float prior, float observed, uint pixels) {
  float from = previous > 0.0 ? previous : prior;
  float share = pixels >= RB_PROBE_TRUSTED_PIXELS ? 0.5 : pixels >= RB_PROBE_TRUSTED_PIXELS / 4u ? 0.25 : 0.125;
  return from + (observed - from) * share;
}

// Item `effect` of object i: learns from last frame's counters, restarts them, and returns
// its candidate's cost and value and its fill share (false: not a candidate).
bool itemCandidate(uint i, uint effect, GpuObjectRecord r, out float cost, out float value, out float fill) {
  uint id = i * RB_ITEMS_PER_OBJECT + effect;
  GpuItemCost c = items[id];
  fill = fillShare(effect, 0.0, 0.0);
  bool learnBenefit = (push.items.w & RB_BENEFIT_PRIOR_ONLY) == 0u;
  // Rays per pixel before anything was measured (shared/selection.h).
  float rays = float(RB_ITEM_PRIOR_RAYS(push.items.y, effect));
  float priorPerPixel = rays * push.budget.w;
  uint rate = c.selectedLast == 0u ? RB_RATE_FULL : c.selectedLast - 1u;  // (1 + its rate; 0: probed)
  bool useTicks = (push.items.w & RB_ITEM_COSTS_UNTIMED) == 0u;
  if (c.pixels > 0u) {  // traced last frame
    // Its cost per pixel: its time, in work units (RB_WORK_PER_CLOCK_UNIT: shading, texture
    // lookups, the shadow classifier, divergence, what traversal work leaves out), or its
    // traversal work where nothing was timed (or ticks are not to be used: RB_ITEM_COSTS_UNTIMED).
    bool timed = c.ticks > 0u && useTicks;
    if (timed || c.work > 0u) {
      // Timed at a reduced rate (selectedLast: 1 + its rate), per pixel at full rate.
      float observed = timed ? exactQuotient(exactQuotient(float(c.ticks), float(c.pixels)) * RB_WORK_PER_CLOCK_UNIT, tracedPixelCost(rate))
                             : exactQuotient(float(c.work), float(c.pixels));
      c.workPerPixel = c.selectedLast == 0u ? probedWorkPerPixel(c.workPerPixel, priorPerPixel, observed, c.pixels)
                                            : averagedWith(c.workPerPixel, observed);
    }
    if (learnBenefit) {
      float removed = exactQuotient(float(c.error), float(c.pixels) * RB_ERROR_UNITS);
      c.benefit = c.measured != 0u ? 0.5 * (c.benefit + removed) : removed;
      c.measured = 1u;
    }
  }
  // Its cost per pixel its reduced rate skipped (the fill), in the same units.
  if (c.skippedPixels > 0u && c.skippedTicks > 0u && useTicks)
    c.fillPerPixel = averagedWith(c.fillPerPixel, exactQuotient(float(c.skippedTicks), float(c.skippedPixels)) * RB_WORK_PER_CLOCK_UNIT);
  if (c.pixels == 0u || !learnBenefit) {
    // Untraced: drift towards the prior (by a power-of-two share: an exact product, so a
    // fused multiply-add rounds alike), or the prior itself before any measurement.
    float prior = params[i].priors[effect];
    c.benefit = c.measured != 0u ? c.benefit + (prior - c.benefit) * RB_BENEFIT_DRIFT : prior;
  }
  items[id] = GpuItemCost(c.workPerPixel, 0u, 0u, 0u, c.benefit, c.measured, c.selectedLast, 0u, c.fillPerPixel, 0u, 0u);
  uint pixels = itemPixels(i, effect);
  if (r.crCandidatePixels.z < 0.5 || pixels == 0u) return false;
  float perPixel = c.workPerPixel > 0.0 ? c.workPerPixel : priorPerPixel;
  // At a fixed reduced rate its share of the full rate's cost; with rates chosen per item (share
  // 1) the full rate's, which the segments share out.
  fill = fillShare(effect, c.fillPerPixel, c.workPerPixel);
  cost = push.budget.y * (float(pixels) * perPixel * rateShare(push.walk.w, fill));
  // R' = (S·I + E)·K with the hysteresis relative to E (docs/SELECTION.md): E·(1 + S·I)·K,
  // E = A·P·b.
  float A = exactQuotient(float(pixels), float(push.items.z));
  float P = (push.items.w & RB_BENEFIT_WITHOUT_CENTRALITY) != 0u ? 1.0 : r.apdv.y;
  float E = A * P * c.benefit;
  vec4 kqiS = params[i].kqiS;
  float I = (push.items.w & RB_BENEFIT_WITHOUT_HYSTERESIS) != 0u ? 0.0 : kqiS.z;
  value = E * (1.0 + (c.selectedLast != 0u ? 1.0 : 0.0) * I) * kqiS.x;
  return true;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.walk.z) return;
  selected[i] = 0u;  // until the walk selects it
  GpuObjectCost oc = costs[i];
  if (oc.pixels > 0u && oc.work > 0u) {
    float observed = exactQuotient(float(oc.work), float(oc.pixels));
    oc.workPerPixel = averagedWith(oc.workPerPixel, observed);
  }
  costs[i] = GpuObjectCost(oc.workPerPixel, 0u, 0u, 0u);
  GpuObjectRecord r = records[i];
  if (push.sizes.z == RB_SELECT_BENEFIT) {
    for (uint effect = 0u; effect < RB_ITEMS_PER_OBJECT; ++effect) {
      float cost = 0.0, value = 0.0, fill = 0.0;
      bool add = itemCandidate(i, effect, r, cost, value, fill);
      uint item = i * RB_ITEMS_PER_OBJECT + effect;
      if (!rateSegmentsWalk()) {
        append(add, item, cost, value, r.apdv.z);
        continue;
      }
      // Rates chosen per item: a candidate per segment of the item's hull (shared/selection.h).
      vec2 q = itemFillQualities(i, effect);
      uint hull = rateHull(q, fill);
      for (uint k = 0u; k < 3u; ++k)
        append(add && k < rateSegments(hull), item * RB_SEGMENT_SLOTS + k, cost * segmentCostShare(k, fill, hull),
               value * segmentValueShare(k, hull, q), r.apdv.z);
    }
    return;
  }
  float pixels = float(floatBitsToUint(r.crCandidatePixels.w));
  float perPixel = oc.workPerPixel > 0.0 ? oc.workPerPixel : params[i].kqiS.y * push.budget.w;
  float work = push.sizes.z == RB_SELECT_PAPER ? r.crCandidatePixels.x : pixels * perPixel;
  bool add = r.crCandidatePixels.z >= 0.5;
  append(add, i, push.budget.y * work, r.crCandidatePixels.y, r.apdv.z);
}
