// The merge sort's shared steps (select_block_sort.comp, select_merge.comp): a sort for CPU
// devices (lavapipe) with no shared memory and few barriers, where a workgroup barrier
// switches between the workgroup's SIMD batches in software and the bitonic sort's
// barrier-heavy stages cost more than the sorting. Keys ping-pong between the order being
// sorted (order, or relevance with stage.z = 1) and the spare buffer.
#ifndef RB_SELECT_MERGE_GLSL
#define RB_SELECT_MERGE_GLSL
#include "select_common.glsl"

layout(set = 0, binding = 10, std430) buffer SpareBlock { uvec2 spare[]; };
// Per order and merge pass, its indirect dispatch (x, y, z, unused), written by the block sort.
layout(set = 0, binding = 12, std430) buffer MergeArgsBlock { uvec4 mergeArgs[]; };

uvec2 loadKey(bool fromSpare, uint i) {
  if (fromSpare) return spare[i];
  return push.stage.z == 0u ? order[i] : relevance[i];
}
void storeKey(bool toSpare, uint i, uvec2 v) {
  if (toSpare) spare[i] = v;
  else if (push.stage.z == 0u) order[i] = v;
  else relevance[i] = v;
}

// The merge levels n candidates need, counted on the GPU (in frame mode only it knows n; the
// host records a merge pass for every level the objects could need, and the block sort
// empties the indirect dispatches of those the candidates do not):
// within a block, runs of RB_MERGE_CHUNK doubled up to the block or n; then merge passes
// over blocks while a run is shorter than n. The last level writes the keys; the first
// writes where that parity needs (spareFirst).
uint levelsInBlock(uint n) {
  uint levels = 0u;
  for (uint run = RB_MERGE_CHUNK; run < min(uint(RB_MERGE_BLOCK), n); run *= 2u) ++levels;
  return levels;
}
uint mergePasses(uint n) {
  uint passes = 0u;
  for (uint run = RB_MERGE_BLOCK; run < n; run *= 2u) ++passes;
  return passes;
}
bool spareFirst(uint n) { return ((levelsInBlock(n) + mergePasses(n)) & 1u) != 0u; }

// Writes outputs [first, last) of the pass that merges runs of `run` sorted keys pairwise
// into runs of 2 run, reading one buffer and writing the other. For each pair of runs it
// touches, it finds where its outputs start on the merge path (one binary search; keys
// are unique: their second word is the candidate's place in ID order), then merges sequentially.
void mergeRange(uint first, uint last, uint run, uint n, bool fromSpare) {
  last = min(last, n);
  uint o = first;
  while (o < last) {
    uint a0 = (o / (2u * run)) * (2u * run), b0 = min(a0 + run, n), end = min(a0 + 2u * run, n);
    uint sizeA = b0 - a0, sizeB = end - b0, d = o - a0;
    // Merge path: how many of the first d outputs come from the first run.
    uint lo = d > sizeB ? d - sizeB : 0u, hi = min(d, sizeA);
    while (lo < hi) {
      uint mid = (lo + hi) / 2u;
      if (keyLess(loadKey(fromSpare, a0 + mid), loadKey(fromSpare, b0 + d - mid - 1u))) lo = mid + 1u;
      else hi = mid;
    }
    uint a = a0 + lo, b = b0 + d - lo;
    uvec2 keyA = a < b0 ? loadKey(fromSpare, a) : uvec2(0u), keyB = b < end ? loadKey(fromSpare, b) : uvec2(0u);
    uint stop = min(last, end);
    // Branch-free steps: one store and at most one load each, whichever run is taken.
    for (; o < stop; ++o) {
      bool takeA = b >= end || (a < b0 && keyLess(keyA, keyB));
      storeKey(!fromSpare, o, takeA ? keyA : keyB);
      a += takeA ? 1u : 0u;
      b += takeA ? 0u : 1u;
      uint next = takeA ? a : b;
      uvec2 v = next < (takeA ? b0 : end) ? loadKey(fromSpare, next) : uvec2(0u);
      keyA = takeA ? v : keyA;
      keyB = takeA ? keyB : v;
    }
  }
}

#endif
