#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_EXT_control_flow_attributes : require
// The sequential part of the selection, one subgroup: the greedy fill-in over the sorted
// order (density, nearest, random; density then compares with the best single candidate),
// or the walk of the paper's graph over the cost chain and the relevance order. The same
// float operations in the same order as engine/src/select (the tests compare bit for bit).
// Writes every candidate's flag (0 or 1) for select(), or in frame mode marks the selected
// objects in the frame's selection (zeroed by select_candidates.comp), nothing else reads
// the flags there. With `benefit` in frame mode it then sets the frame's probe stride.
#include "include/select_common.glsl"
#include "include/select_apply.glsl"
#include "include/order_free_sum.glsl"

// The device's subgroup size: the workgroup is one subgroup (were it more, each would walk
// the same order to the same selection and write the same values).
layout(local_size_x_id = 0) in;

// What was selected: predicted cost and value summed in selection order (or, where everything
// is, in none), and the count.
struct Picked {
  float cost, value;
  uint count;
};

void mark(uint ci, uint id, bool on) {
  if (push.walk.y == 0u) selectedFlags[ci] = on ? 1u : 0u;
  else if (on && !rateSegmentsWalk()) markSelected(id);  // segments: by the items' levels (markLevels)
}
void mark(uint ci, bool on) { mark(ci, candidates[ci].id, on); }

// Every candidate unselected (the frame's selection too), before density's best single
// candidate replaces the greedy selection.
void clearAll(uint n) {
  for (uint ci = gl_SubgroupInvocationID; ci < n; ci += gl_SubgroupSize) {
    if (push.walk.y == 0u) selectedFlags[ci] = 0u;
    else if (!rateSegmentsWalk()) clearSelected(candidates[ci].id);
  }
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
}

// Rate segments (`benefit` with RB_RATE_AUTO): each item's level, the segments taken so far,
// in scratch[item]. Every lane writes the same levels and reads only its own writes.
uint segmentGroups() { return push.walk.y != 0u ? push.walk.z * RB_ITEMS_PER_OBJECT : push.stage.w; }
void clearLevels() {
  for (uint g = gl_SubgroupInvocationID; g < segmentGroups(); g += gl_SubgroupSize) scratch[g] = 0u;
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
}
// Whether segment `id` may be taken: its item has taken the segments before it.
bool segmentNext(uint id) { return scratch[id / RB_SEGMENT_SLOTS] == id % RB_SEGMENT_SLOTS; }

// Frame mode: marks each item with a level in the frame's selection, with the rate its last
// segment reaches.
void markLevels() {
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
  for (uint item = gl_SubgroupInvocationID; item < segmentGroups(); item += gl_SubgroupSize) {
    uint effect = item % RB_ITEMS_PER_OBJECT, level = scratch[item];
    if (level == 0u) continue;
    uint rate = segmentRate(level - 1u, itemHull(item));
    atomicOr(selected[item / RB_ITEMS_PER_OBJECT], (1u << effect) | (rate << (RB_RATE_SHIFT + 2u * effect)));
  }
}

// The best single candidate that fits, as a lane sees it (the CPU reference's: higher
// value, then lower ID, then the first in candidate order).
struct Single {
  uint found;  // 0 or 1 (a bool member makes glslang emit invalid SPIR-V)
  float value;
  uint id, index;
};

bool betterSingle(GpuCandidate c, uint ci, Single b) {
  if (b.found == 0u || c.value > b.value) return true;
  if (c.value < b.value) return false;
  return c.id < b.id || (c.id == b.id && ci < b.index);
}

// `benefit` in frame mode with rates chosen per item: the first item in the walk's order whose
// first segment did not fit, its cost and value, and the budget the walk had left then (the
// same in every lane); traced on a share of its tiles (shared/selection.h,
// RB_PARTIAL_MIN_SHARE). Where that share is taken the walk stops there: what follows in the
// order is worth less per cost (the fractional knapsack's greedy; policies.cpp's reference).
uint partialId = RB_NO_PARTIAL;
float partialCost = 0.0, partialValue = 0.0, leftOver = 0.0;
bool partialWanted() { return push.walk.y != 0u && rateSegmentsWalk(); }
// Whether `left` pays for RB_PARTIAL_MIN_SHARE of a candidate of `cost`.
bool sharePays(float left, float cost) { return exactQuotient(left, cost) >= RB_PARTIAL_MIN_SHARE; }
// Records candidate `id`, which did not fit, as the partial item with the budget left now; where
// that pays for RB_PARTIAL_MIN_SHARE of it, nothing more goes in.
void recordPartial(uint id, float cost, float value, inout float remaining) {
  partialId = id;
  partialCost = cost;
  partialValue = value;
  leftOver = remaining;
  if (sharePays(remaining, cost)) remaining = 0.0;
}
// The partial item's share of its tiles: 0 where there is none or under RB_PARTIAL_MIN_SHARE.
float partialShare() {
  float share = partialId != RB_NO_PARTIAL ? exactQuotient(leftOver, partialCost) : 0.0;
  return share >= RB_PARTIAL_MIN_SHARE ? share : 0.0;
}
// Whether candidate `id` may become the partial one: the first segment of a reflection or
// refraction item (the first rate on its hull). Shadow items in the walk's order too lost: on
// AlphaBlendModeTest's orbit a partial shadow item took the budget a mirror's share had, for
// no change in the image (error recovered at 25% 0.23 to 0.03, two repeats each). So the
// first shadow item whose first segment did not fit gets only what the whole walk left, where
// no reflection or refraction item took it (a scene whose error is one large shadow item,
// CesiumMilkTruck's, else traces nothing below its first segment's cost).
bool partialCandidate(uint id) {
  return id % RB_SEGMENT_SLOTS == 0u && candidateItem(id) % RB_ITEMS_PER_OBJECT != RB_ITEM_SHADOWS;
}
bool shadowPartialCandidate(uint id) {
  return id % RB_SEGMENT_SLOTS == 0u && candidateItem(id) % RB_ITEMS_PER_OBJECT == RB_ITEM_SHADOWS;
}
uint shadowPartialId = RB_NO_PARTIAL;
float shadowPartialCost = 0.0, shadowPartialValue = 0.0;
void recordShadowPartial(uint id, float cost, float value) {
  shadowPartialId = id;
  shadowPartialCost = cost;
  shadowPartialValue = value;
}
// After the walk: the shadow item takes what was left where no other partial item did.
void takeShadowPartial(float remaining) {
  if (partialShare() > 0.0 || shadowPartialId == RB_NO_PARTIAL || !sharePays(remaining, shadowPartialCost)) return;
  partialId = shadowPartialId;
  partialCost = shadowPartialCost;
  partialValue = shadowPartialValue;
  leftOver = remaining;
}

// The greedy fill-in, a subgroup's batch of the order at a time: the lanes load their
// candidates together (the next batch's load in flight while this one decides), and the
// decisions run in order on values shuffled from each lane, so the remaining budget is the
// same float sequence as the CPU's. A batch where nothing fits any more is skipped (most of
// them once the budget is spent). Density also keeps, per lane, the best single candidate
// that fits; the subgroup then picks the best of those.
Picked selectGreedy(uint n, float budget) {
  Picked p = Picked(0.0, 0.0, 0u);
  bool density = push.sizes.z == RB_SELECT_DENSITY || push.sizes.z == RB_SELECT_BENEFIT;
  bool segments = rateSegmentsWalk();
  float remaining = budget;
  uint lane = gl_SubgroupInvocationID;
  Single best = Single(0u, 0.0, 0u, 0u);
  uvec4 next = lane < n ? walkOrder[lane] : uvec4(0u);
  for (uint base = 0u; base < n; base += gl_SubgroupSize) {
    bool valid = base + lane < n;
    uvec4 record = next;
    if (base + gl_SubgroupSize + lane < n) next = walkOrder[base + gl_SubgroupSize + lane];
    uint ci = record.z;
    // Past the end: fits nothing.
    GpuCandidate c = GpuCandidate(record.w, valid ? uintBitsToFloat(record.x) : uintBitsToFloat(0x7F800000u), uintBitsToFloat(record.y), 0.0);
    bool taken = false;
    bool eligible = valid && partialWanted() && partialCandidate(c.id);
    bool shadowEligible = valid && partialWanted() && shadowPartialCandidate(c.id);
    if (subgroupAny(c.cost <= remaining)) {
      uint count = min(gl_SubgroupSize, n - base);
      // Unrolled to the subgroup size (a specialization constant): a GPU then issues the
      // shuffles ahead of the decisions that wait on them (H100, 10k: 0.30 -> 0.24 ms).
      [[unroll]] for (uint j = 0u; j < gl_WorkGroupSize.x; ++j) {
        if (j >= count) break;
        float cost = subgroupShuffle(c.cost, j), value = subgroupShuffle(c.value, j);
        uint id = subgroupShuffle(c.id, j);
        // A rate segment goes only onto its item's previous one (the hull's next step).
        if (cost <= remaining && (!segments || segmentNext(id))) {
          remaining -= cost;
          p.cost += cost;
          p.value += value;
          ++p.count;
          taken = taken || lane == j;
          if (segments) scratch[id / RB_SEGMENT_SLOTS] = id % RB_SEGMENT_SLOTS + 1u;
        } else if (partialId == RB_NO_PARTIAL && subgroupShuffle(eligible, j)) {
          recordPartial(id, cost, value, remaining);
        } else if (shadowPartialId == RB_NO_PARTIAL && subgroupShuffle(shadowEligible, j)) {
          recordShadowPartial(id, cost, value);
        }
      }
    } else {  // nothing here fits: the first eligible ones
      if (partialId == RB_NO_PARTIAL && subgroupAny(eligible)) {
        uint first = subgroupBallotFindLSB(subgroupBallot(eligible));
        recordPartial(subgroupShuffle(c.id, first), subgroupShuffle(c.cost, first), subgroupShuffle(c.value, first), remaining);
      }
      if (shadowPartialId == RB_NO_PARTIAL && subgroupAny(shadowEligible)) {
        uint first = subgroupBallotFindLSB(subgroupBallot(shadowEligible));
        recordShadowPartial(subgroupShuffle(c.id, first), subgroupShuffle(c.cost, first), subgroupShuffle(c.value, first));
      }
    }
    if (valid) mark(ci, c.id, taken);
    // Rate segments: a single option is an item's first segment (the others build on it).
    bool single = !segments || c.id % RB_SEGMENT_SLOTS == 0u;
    if (density && valid && single && c.cost <= budget && betterSingle(c, ci, best)) best = Single(1u, c.value, c.id, ci);
  }
  takeShadowPartial(remaining);
  bool found = best.found != 0u;
  if (!subgroupAny(found)) return p;
  // The subgroup's best: highest value, then lowest ID, then lowest index.
  float topValue = subgroupMax(found ? best.value : uintBitsToFloat(0xFF800000u));
  bool top = found && best.value == topValue;
  uint topId = subgroupMin(top ? best.id : 0xFFFFFFFFu);
  uint winner = subgroupMin(top && best.id == topId ? best.index : 0xFFFFFFFFu);
  precise float withPartial = p.value + partialValue * partialShare();
  if (topValue <= withPartial) return p;
  partialId = RB_NO_PARTIAL;  // the best single candidate instead of the greedy selection
  clearAll(n);
  if (segments) {
    clearLevels();
    scratch[candidates[winner].id / RB_SEGMENT_SLOTS] = 1u;
  }
  if (lane == 0u) mark(winner, true);
  return Picked(candidates[winner].cost, topValue, 1u);
}

// The lowest position in [from, end) of `paper`'s cost chain (offset 0) or relevance order
// (offset padded) whose node is untaken and fits, with its record (select_gather.comp); pos
// = end if none. The subgroup tests its lanes' positions together and the ballot's lowest lane
// wins: per batch one record load and one flag load, whatever the position.
struct Found {
  uint pos;
  uvec4 record;  // cost, slot, pointer window, value
};

Found firstThatFits(uint offset, uint from, uint end, float remaining) {
  for (uint base = from; base < end; base += gl_SubgroupSize) {
    uint pos = base + gl_SubgroupInvocationID;
    uvec4 record = uvec4(0u);
    bool fits = false;
    if (pos < end) {
      record = walkOrder[offset + pos];
      fits = uintBitsToFloat(record.x) <= remaining && scratch[record.y] == 0u;
    }
    uvec4 ballot = subgroupBallot(fits);
    if (ballot != uvec4(0u)) {
      uint winner = subgroupBallotFindLSB(ballot);
      return Found(base + winner, subgroupShuffle(record, winner));
    }
  }
  return Found(end, uvec4(0u));
}

// The walk over the cost chain and the pointers into the relevance order. It is sequential:
// every lane walks it (same values, same floats), and the lanes split each scan for the next
// node that fits. scratch[0, n): taken, set by every lane itself (each reads only its own
// writes after the clearing barrier); the selection is marked from it at the end.
Picked selectPaper(uint n, float budget, uint pointers) {
  Picked p = Picked(0.0, 0.0, 0u);
  uint lane = gl_SubgroupInvocationID, relevanceOffset = push.sizes.y;
  for (uint ci = lane; ci < n; ci += gl_SubgroupSize) scratch[ci] = 0u;
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
  float remaining = budget;
  uint head = 0u;
  while (p.count < n) {  // each pick takes a node: a bound, were the flags ever wrong, not a hang
    // Nodes too costly for what is left go to the next frame's graph: the budget only
    // shrinks, so they cannot fit later in this frame either.
    Found node = firstThatFits(0u, head, n, remaining);
    head = node.pos;
    if (head >= n) break;
    for (uint hop = 0u; push.walk.x == 0u || hop < push.walk.x; ++hop) {
      uint first = node.record.z;
      Found pointer = firstThatFits(relevanceOffset, first > pointers ? first - pointers : 0u, first, remaining);  // most relevant first
      if (pointer.pos == first) break;
      node.record = pointer.record;
    }
    scratch[node.record.y] = 1u;
    float cost = uintBitsToFloat(node.record.x);
    p.cost += cost;
    p.value += uintBitsToFloat(node.record.w);
    ++p.count;
    remaining -= cost;
  }
  for (uint ci = lane; ci < n; ci += gl_SubgroupSize) mark(ci, scratch[ci] != 0u);
  return p;
}

// Frame mode: the largest candidate's cost, which the candidate pass kept, the scale of the
// walk's cost sums in no order.
float largestCandidateCost() { return uintBitsToFloat(result4.x); }

// `benefit`, frame mode, after the walk: the probe stride for what the walk left out (the
// least that keeps its predicted cost within the probe budget, shared/selection.h), kept in
// the items' totals record for the tile list and the trace passes; the probe's predicted cost.
float setProbeStride(uint n) {
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();  // the lanes' marks in the frame's selection are visible
  float largest = largestCandidateCost(), scale = fixedScale(largest);
  uvec3 laneParts = uvec3(0u);
  for (uint ci = gl_SubgroupInvocationID; ci < n; ci += gl_SubgroupSize)  // (a left-out item's segments add up to its full cost)
    if (!itemMarked(candidateItem(candidates[ci].id))) laneParts += fixedParts(candidates[ci].cost, scale);
  float left = fixedSum(laneParts, largest), budget = push.budget.z;
  uint stride = 0u;
  if (left > 0.0 && budget > 0.0) {
    float ratio = ceil(exactQuotient(left, budget));
    stride = ratio <= float(RB_PROBE_MAX_STRIDE) ? max(uint(ratio), 1u) : 0u;
  }
  if (gl_SubgroupInvocationID == 0u) items[push.walk.z * RB_ITEMS_PER_OBJECT].pixels = stride;
  return stride == 0u ? 0.0 : left / float(stride);
}

// Whether candidate `id` was selected and is priced by the prior (its learned work per pixel is 0).
bool pricedByThePrior(uint id, uint policy) {
  if (policy != RB_SELECT_BENEFIT) return (selected[id] & RB_ITEMS_ALL) != 0u && costs[id].workPerPixel == 0.0;
  uint item = candidateItem(id);
  bool taken = rateSegmentsWalk() ? scratch[item] > id % RB_SEGMENT_SLOTS : itemMarked(item);
  return taken && items[item].workPerPixel == 0.0;
}

// Frame mode, after the walk: the predicted cost of the selected candidates whose item (or
// object) was never traced, priced by the prior (its learned work per pixel is 0). The time
// scale leaves frames mostly priced so out of the headroom (cost_model.h): the prior's error
// is a bias the first traced frame removes, not the noise the headroom is for. `paper`'s cost
// is the paper's C, never learned: 0.
float priorPricedCost(uint n) {
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();  // the lanes' marks in the frame's selection (or the items' levels) are visible
  uint policy = push.sizes.z;
  if (policy == RB_SELECT_PAPER || policy == RB_SELECT_NONE) return 0.0;
  float largest = largestCandidateCost(), scale = fixedScale(largest);
  uvec3 laneParts = uvec3(0u);
  for (uint ci = gl_SubgroupInvocationID; ci < n; ci += gl_SubgroupSize)
    if (pricedByThePrior(candidates[ci].id, policy)) laneParts += fixedParts(candidates[ci].cost, scale);
  return fixedSum(laneParts, largest);
}

void main() {
  uint n = candidateCount(), policy = push.sizes.z;
  float budget = push.budget.x;
  Picked p = Picked(0.0, 0.0, 0u);
  bool everything = policy == RB_SELECT_ALL || allCandidatesFit();  // (no order needed)
  if (rateSegmentsWalk()) clearLevels();
  if (everything || policy == RB_SELECT_NONE) {
    // Everything is taken: its cost and value are summed in no order (include/order_free_sum.glsl),
    // at the scale of the largest term: in frame mode the candidate pass kept them, select()'s
    // are found here.
    float largestCost = largestCandidateCost(), largestValue = uintBitsToFloat(result4.y);
    if (push.walk.y == 0u) {
      float laneCost = 0.0, laneValue = 0.0;
      for (uint ci = gl_SubgroupInvocationID; everything && ci < n; ci += gl_SubgroupSize) {
        laneCost = largerTerm(laneCost, candidates[ci].cost);
        laneValue = largerTerm(laneValue, candidates[ci].value);
      }
      largestCost = subgroupLargest(laneCost);
      largestValue = subgroupLargest(laneValue);
    }
    float costScale = fixedScale(largestCost), valueScale = fixedScale(largestValue);
    uvec3 costParts = uvec3(0u), valueParts = uvec3(0u);
    uint laneCount = 0u;
    // Four candidates per lane and step, their loads issued together: one subgroup walks
    // them all, so on a GPU each step's load latency, not the work, sets the pace.
    for (uint base = 0u; base < n; base += 4u * gl_SubgroupSize) {
      GpuCandidate c[4];
      [[unroll]] for (uint k = 0u; k < 4u; ++k) {
        uint ci = base + k * gl_SubgroupSize + gl_SubgroupInvocationID;
        if (ci < n) c[k] = candidates[ci];
      }
      [[unroll]] for (uint k = 0u; k < 4u; ++k) {
        uint ci = base + k * gl_SubgroupSize + gl_SubgroupInvocationID;
        if (ci >= n) continue;
        mark(ci, c[k].id, everything);
        if (everything && rateSegmentsWalk()) atomicMax(scratch[c[k].id / RB_SEGMENT_SLOTS], c[k].id % RB_SEGMENT_SLOTS + 1u);
        if (everything) {
          costParts += fixedParts(c[k].cost, costScale);
          valueParts += fixedParts(c[k].value, valueScale);
          ++laneCount;
        }
      }
    }
    p = Picked(fixedSum(costParts, largestCost), fixedSum(valueParts, largestValue), subgroupAdd(laneCount));
  } else if (policy == RB_SELECT_PAPER) {
    p = selectPaper(n, budget, push.stage.w);
  } else {
    p = selectGreedy(n, budget);
  }
  // The partial item: its first segment on the share of its tiles the budget left pays for.
  float share = partialShare();
  if (share > 0.0) {
    scratch[partialId / RB_SEGMENT_SLOTS] = 1u;  // every lane writes the same level
    p.cost += leftOver;
    p.value += partialValue * share;
    ++p.count;
  } else {
    partialId = RB_NO_PARTIAL;
  }
  if (push.walk.y != 0u && gl_SubgroupInvocationID == 0u) {  // for the tile list and the trace passes (every frame mode policy)
    items[push.walk.z * RB_ITEMS_PER_OBJECT].selectedLast = partialId == RB_NO_PARTIAL ? 0u : partialId / RB_SEGMENT_SLOTS + 1u;
    items[push.walk.z * RB_ITEMS_PER_OBJECT].benefit = share;
  }
  if (rateSegmentsWalk() && push.walk.y != 0u) markLevels();
  // The predicted cost includes the probe's (the time scale learns from the trace time).
  if (policy == RB_SELECT_BENEFIT && push.walk.y != 0u) p.cost += setProbeStride(n);
  float prior = push.walk.y != 0u ? priorPricedCost(n) : 0.0;
  if (gl_SubgroupInvocationID == 0u) {
    result.yzw = uvec3(floatBitsToUint(p.cost), floatBitsToUint(p.value), p.count);
    result3.y = floatBitsToUint(prior);
    result3.z = floatBitsToUint(share);  // the partial item's share of its tiles (0: none)
    result2.w = everything || policy == RB_SELECT_NONE ? 0u : 1u;  // the selection needed an order
  }
  // Few objects: the selection applied here (include/select_apply.glsl), once every lane's
  // marks and the probe stride are visible, instead of in a dispatch of its own.
  if (push.walk.y != 0u && push.stage.x == RB_APPLY_IN_WALK) {
    subgroupMemoryBarrierBuffer();
    subgroupBarrier();
    for (uint i = gl_SubgroupInvocationID; i < push.walk.z; i += gl_SubgroupSize) applySelection(i);
  }
}
