#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_shuffle : require
// The sequential part of the selection, one subgroup: the greedy fill-in over the sorted
// order (density, nearest, random; density then compares with the best single candidate),
// or the walk of the paper's graph over the cost chain and the relevance order. The same
// float operations in the same order as engine/src/select (the tests compare bit for bit).
// Writes every candidate's flag (0 or 1) for select(), or in frame mode marks the selected
// objects in the frame's selection (zeroed by select_candidates.comp), nothing else reads
// the flags there.
#include "include/select_common.glsl"

// The device's subgroup size: the workgroup is one subgroup (were it more, each would walk
// the same order to the same selection and write the same values).
layout(local_size_x_id = 0) in;

// What was selected: predicted cost and value summed in selection order, and the count.
struct Picked {
  float cost, value;
  uint count;
};

void mark(uint ci, bool on) {
  if (push.walk.y == 0u) selectedFlags[ci] = on ? 1u : 0u;
  else if (on) selected[candidates[ci].id] = 1u;
}

// Every candidate unselected (the frame's selection too), before a walk or a replacement.
void clearAll(uint n) {
  for (uint ci = gl_SubgroupInvocationID; ci < n; ci += gl_SubgroupSize) {
    if (push.walk.y == 0u) selectedFlags[ci] = 0u;
    else selected[candidates[ci].id] = 0u;
  }
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
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

// The greedy fill-in, a subgroup's batch of the order at a time: the lanes load their
// candidates together, and the decisions run in order on values shuffled from each lane,
// so the remaining budget is the same float sequence as the CPU's. A batch where nothing
// fits any more is skipped (most of them once the budget is spent). Density also keeps,
// per lane, the best single candidate that fits; the subgroup then picks the best of those.
Picked selectGreedy(uint n, float budget) {
  Picked p = Picked(0.0, 0.0, 0u);
  bool density = push.sizes.z == RB_SELECT_DENSITY;
  float remaining = budget;
  uint lane = gl_SubgroupInvocationID;
  Single best = Single(0u, 0.0, 0u, 0u);
  for (uint base = 0u; base < n; base += gl_SubgroupSize) {
    bool valid = base + lane < n;
    uint ci = valid ? candidateAt(order[base + lane].y) : 0u;
    GpuCandidate c = GpuCandidate(0u, uintBitsToFloat(0x7F800000u), 0.0, 0.0);  // past the end: fits nothing
    if (valid) c = candidates[ci];  // (not a ?: with the buffer's struct: glslang emits invalid SPIR-V)
    bool taken = false;
    if (subgroupAny(c.cost <= remaining)) {
      uint count = min(gl_SubgroupSize, n - base);
      for (uint j = 0u; j < count; ++j) {
        float cost = subgroupShuffle(c.cost, j), value = subgroupShuffle(c.value, j);
        if (cost <= remaining) {
          remaining -= cost;
          p.cost += cost;
          p.value += value;
          ++p.count;
          taken = taken || lane == j;
        }
      }
    }
    if (valid) mark(ci, taken);
    if (density && valid && c.cost <= budget && betterSingle(c, ci, best)) best = Single(1u, c.value, c.id, ci);
  }
  bool found = best.found != 0u;
  if (!subgroupAny(found)) return p;
  // The subgroup's best: highest value, then lowest ID, then lowest index.
  float topValue = subgroupMax(found ? best.value : uintBitsToFloat(0xFF800000u));
  bool top = found && best.value == topValue;
  uint topId = subgroupMin(top ? best.id : 0xFFFFFFFFu);
  uint winner = subgroupMin(top && best.id == topId ? best.index : 0xFFFFFFFFu);
  if (topValue <= p.value) return p;
  clearAll(n);
  if (lane == 0u) mark(winner, true);
  return Picked(candidates[winner].cost, topValue, 1u);
}

// scratch: [0, n) taken, [n, 2n) rank in the relevance order, [2n, 3n) first position of
// the rank's group of equal relevance. Sequential, on the subgroup's first lane.
Picked selectPaper(uint n, float budget, uint pointers) {
  Picked p = Picked(0.0, 0.0, 0u);
  for (uint ci = gl_SubgroupInvocationID; ci < n; ci += gl_SubgroupSize) scratch[ci] = 0u;
  if (push.walk.y == 0u) {
    clearAll(n);  // the flags; in frame mode the candidate pass cleared the selection
  } else {
    subgroupMemoryBarrierBuffer();
    subgroupBarrier();
  }
  if (gl_SubgroupInvocationID != 0u) return p;
  for (uint s = 0u; s < n; ++s) {
    uint ci = candidateAt(relevance[s].y);
    scratch[n + ci] = s;
    bool tie = s > 0u && candidates[candidateAt(relevance[s - 1u].y)].value == candidates[ci].value;
    scratch[2u * n + s] = tie ? scratch[2u * n + s - 1u] : s;
  }
  float remaining = budget;
  uint head = 0u;
  while (true) {
    while (head < n && (scratch[candidateAt(order[head].y)] != 0u || candidates[candidateAt(order[head].y)].cost > remaining)) ++head;
    if (head == n) break;
    uint node = candidateAt(order[head].y);
    for (uint hop = 0u; push.walk.x == 0u || hop < push.walk.x; ++hop) {
      bool climbed = false;
      uint first = scratch[2u * n + scratch[n + node]];
      uint from = first > pointers ? first - pointers : 0u;
      for (uint pos = from; pos < first; ++pos) {  // most relevant first
        uint c = candidateAt(relevance[pos].y);
        if (scratch[c] != 0u || candidates[c].cost > remaining) continue;
        node = c;
        climbed = true;
        break;
      }
      if (!climbed) break;
    }
    scratch[node] = 1u;
    mark(node, true);
    p.cost += candidates[node].cost;
    p.value += candidates[node].value;
    ++p.count;
    remaining -= candidates[node].cost;
  }
  return p;
}

void main() {
  uint n = candidateCount(), policy = push.sizes.z;
  float budget = push.budget.x;
  Picked p = Picked(0.0, 0.0, 0u);
  bool everything = policy == RB_SELECT_ALL || allCandidatesFit();  // (no order needed)
  if (everything || policy == RB_SELECT_NONE) {
    Picked lanePart = Picked(0.0, 0.0, 0u);
    for (uint ci = gl_SubgroupInvocationID; ci < n; ci += gl_SubgroupSize) {
      mark(ci, everything);
      if (everything) lanePart = Picked(lanePart.cost + candidates[ci].cost, lanePart.value + candidates[ci].value, lanePart.count + 1u);
    }
    p = Picked(subgroupAdd(lanePart.cost), subgroupAdd(lanePart.value), subgroupAdd(lanePart.count));
  } else if (policy == RB_SELECT_PAPER) {
    p = selectPaper(n, budget, push.stage.w);
  } else {
    p = selectGreedy(n, budget);
  }
  if (gl_SubgroupInvocationID == 0u) {
    result.yzw = uvec3(floatBitsToUint(p.cost), floatBitsToUint(p.value), p.count);
    result2.w = everything || policy == RB_SELECT_NONE ? 0u : 1u;  // the selection needed an order
  }
}
