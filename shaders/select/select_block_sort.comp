#version 460
#extension GL_GOOGLE_include_directive : require
// The merge sort's first dispatch: each workgroup sorts one block of RB_MERGE_BLOCK
// candidates' keys completely. The workgroup is one SIMD batch on lavapipe
// (RB_MERGE_LANES invocations), so its barriers switch nothing; the merge passes of
// select_merge.comp then merge the blocks. Each invocation computes the keys of chunks of
// 8 and sorts them with a sorting network on registers (no array indexed at run time:
// lavapipe would spill it), then every level merges runs of 8, 16, ... up to the block.
// The sorted chunks go to the spare buffer or the keys, so that the last level of the
// whole sort writes the keys (select_merge.glsl's spareFirst).
#include "include/select_merge.glsl"

layout(local_size_x = RB_MERGE_LANES) in;

// Compare-exchange: a gets the smaller key.
#define RB_CSWAP(a, b) \
  if (keyLess(b, a)) { \
    uvec2 t = a;       \
    a = b;             \
    b = t;             \
  }

// The RB_MERGE_CHUNK (8) keys of chunk `chunk`, sorted by a 19-comparator network (keys past n are all
// ones, sorted last, not stored).
void sortChunk(uint chunk, uint n, bool toSpare) {
  uint first = chunk * RB_MERGE_CHUNK, which = push.stage.z;
  if (first >= n) return;
  uvec2 k0 = candidateKey(first, which), k1 = candidateKey(first + 1u, which), k2 = candidateKey(first + 2u, which);
  uvec2 k3 = candidateKey(first + 3u, which), k4 = candidateKey(first + 4u, which), k5 = candidateKey(first + 5u, which);
  uvec2 k6 = candidateKey(first + 6u, which), k7 = candidateKey(first + 7u, which);
  RB_CSWAP(k0, k2) RB_CSWAP(k1, k3) RB_CSWAP(k4, k6) RB_CSWAP(k5, k7)
  RB_CSWAP(k0, k4) RB_CSWAP(k1, k5) RB_CSWAP(k2, k6) RB_CSWAP(k3, k7)
  RB_CSWAP(k0, k1) RB_CSWAP(k2, k3) RB_CSWAP(k4, k5) RB_CSWAP(k6, k7)
  RB_CSWAP(k2, k4) RB_CSWAP(k3, k5)
  RB_CSWAP(k1, k4) RB_CSWAP(k3, k6)
  RB_CSWAP(k1, k2) RB_CSWAP(k3, k4) RB_CSWAP(k5, k6)
  storeKey(toSpare, first, k0);
  if (first + 1u < n) storeKey(toSpare, first + 1u, k1);
  if (first + 2u < n) storeKey(toSpare, first + 2u, k2);
  if (first + 3u < n) storeKey(toSpare, first + 3u, k3);
  if (first + 4u < n) storeKey(toSpare, first + 4u, k4);
  if (first + 5u < n) storeKey(toSpare, first + 5u, k5);
  if (first + 6u < n) storeKey(toSpare, first + 6u, k6);
  if (first + 7u < n) storeKey(toSpare, first + 7u, k7);
}

void main() {
  uint n = candidateCount(), base = gl_WorkGroupID.x * RB_MERGE_BLOCK, lane = gl_LocalInvocationID.x;
  // The merge passes' indirect dispatches: workgroups for the candidates, none for a pass
  // they do not need (or when no order is needed at all).
  if (gl_WorkGroupID.x == 0u && lane == 0u) {
    uint passes = allCandidatesFit() ? 0u : mergePasses(n), groups = (n + RB_MERGE_SEGMENT * RB_MERGE_GROUP - 1u) / (RB_MERGE_SEGMENT * RB_MERGE_GROUP);
    for (uint p = 0u; p < RB_MERGE_MAX_PASSES; ++p) mergeArgs[push.stage.z * RB_MERGE_MAX_PASSES + p] = uvec4(p < passes ? groups : 0u, 1u, 1u, 0u);
  }
  if (base >= n || allCandidatesFit()) return;  // the whole workgroup: no barrier is skipped by part of it
  bool toSpare = spareFirst(n);
  // Adjacent lanes take adjacent chunks, so the SIMD batch loads neighbouring candidates.
  for (uint c = lane; c < RB_MERGE_BLOCK / RB_MERGE_CHUNK; c += RB_MERGE_LANES) sortChunk(base / RB_MERGE_CHUNK + c, n, toSpare);
  const uint perLane = RB_MERGE_BLOCK / RB_MERGE_LANES;
  uint run = RB_MERGE_CHUNK;
  for (uint level = 0u, levels = levelsInBlock(n); level < levels; ++level) {
    memoryBarrierBuffer();
    barrier();
    mergeRange(base + lane * perLane, base + (lane + 1u) * perLane, run, n, toSpare);
    toSpare = !toSpare;
    run *= 2u;
  }
  // One block and a greedy policy (the host's choice, stage.y): the walk's records laid out
  // here (select_gather.comp's work), a dispatch saved.
  if (push.stage.y == RB_GATHER_IN_SORT) {
    memoryBarrierBuffer();
    barrier();
    for (uint i = lane; i < n; i += RB_MERGE_LANES) walkOrder[i] = greedyRecord(candidateAt(order[i].y));
  }
}
