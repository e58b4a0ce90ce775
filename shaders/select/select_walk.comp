#version 460
#extension GL_GOOGLE_include_directive : require
// The sequential part of the selection, one invocation: the greedy fill-in over the sorted
// order (density, nearest, random; density then compares with the best single candidate),
// or the walk of the paper's graph over the cost chain and the relevance order. The same
// float operations in the same order as engine/src/select (the tests compare bit for bit).
// The flags and the scratch are zeroed by the host before.
#include "include/select_common.glsl"

layout(local_size_x = 1) in;

void selectGreedy(uint n, float budget) {
  float remaining = budget, greedyValue = 0.0;
  for (uint s = 0u; s < n; ++s) {
    uint ci = order[s].w;
    float cost = candidates[ci].cost;
    if (cost <= remaining) {
      selectedFlags[ci] = 1u;
      remaining -= cost;
      greedyValue += candidates[ci].value;
    }
  }
  if (push.sizes.z != RB_SELECT_DENSITY) return;
  // The best single candidate that fits (ties: lower ID), if it beats the greedy set.
  uint best = 0xFFFFFFFFu;
  for (uint ci = 0u; ci < n; ++ci) {
    GpuCandidate c = candidates[ci];
    if (c.cost > budget) continue;
    if (best == 0xFFFFFFFFu || c.value > candidates[best].value || (c.value == candidates[best].value && c.id < candidates[best].id)) best = ci;
  }
  if (best != 0xFFFFFFFFu && candidates[best].value > greedyValue) {
    for (uint ci = 0u; ci < n; ++ci) selectedFlags[ci] = 0u;
    selectedFlags[best] = 1u;
  }
}

// scratch: [0, n) taken, [n, 2n) rank in the relevance order, [2n, 3n) first position of
// the rank's group of equal relevance.
void selectPaper(uint n, float budget, uint pointers) {
  for (uint s = 0u; s < n; ++s) {
    uint ci = relevance[s].w;
    scratch[n + ci] = s;
    bool tie = s > 0u && candidates[relevance[s - 1u].w].value == candidates[ci].value;
    scratch[2u * n + s] = tie ? scratch[2u * n + s - 1u] : s;
  }
  float remaining = budget;
  uint head = 0u;
  while (true) {
    while (head < n && (scratch[order[head].w] != 0u || candidates[order[head].w].cost > remaining)) ++head;
    if (head == n) break;
    uint node = order[head].w;
    for (uint hop = 0u; push.walk.x == 0u || hop < push.walk.x; ++hop) {
      bool climbed = false;
      uint first = scratch[2u * n + scratch[n + node]];
      uint from = first > pointers ? first - pointers : 0u;
      for (uint pos = from; pos < first; ++pos) {  // most relevant first
        uint p = relevance[pos].w;
        if (scratch[p] != 0u || candidates[p].cost > remaining) continue;
        node = p;
        climbed = true;
        break;
      }
      if (!climbed) break;
    }
    scratch[node] = 1u;
    selectedFlags[node] = 1u;
    remaining -= candidates[node].cost;
  }
}

void main() {
  uint n = candidateCount(), policy = push.sizes.z;
  float budget = push.budget.x;
  if (policy == RB_SELECT_ALL) {
    for (uint ci = 0u; ci < n; ++ci) selectedFlags[ci] = 1u;
  } else if (policy == RB_SELECT_PAPER) {
    selectPaper(n, budget, push.stage.w);
  } else if (policy != RB_SELECT_NONE) {
    selectGreedy(n, budget);
  }
  // What was selected, for the stats and the cost model: predicted cost and value.
  float cost = 0.0, value = 0.0;
  uint count = 0u;
  for (uint ci = 0u; ci < n; ++ci)
    if (selectedFlags[ci] != 0u) {
      cost += candidates[ci].cost;
      value += candidates[ci].value;
      ++count;
    }
  result.yzw = uvec3(floatBitsToUint(cost), floatBitsToUint(value), count);
}
