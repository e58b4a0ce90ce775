#version 460
#extension GL_GOOGLE_include_directive : require
// A merge sort of the candidates' keys (order, or relevance with stage.z = 1) with no
// barrier and no shared memory, for CPU devices (lavapipe), where a workgroup barrier
// switches between the workgroup's SIMD batches in software and the bitonic sort's
// barrier-heavy stages cost more than the sorting. Each invocation writes RB_MERGE_CHUNK
// consecutive outputs: it sorts its chunk first (a sorting network), then in every merge pass finds where its
// outputs start on the merge path of its two runs (one binary search; keys are unique: the
// candidate index is their last word) and merges sequentially from there.
//   stage.x = 0: the chunk sort, in place (stage.y = 0) or into the spare
//   buffer (stage.y = 1).
//   stage.x = L: runs of L keys merged pairwise into runs of 2L, from the keys into the
//   spare buffer (stage.y = 0) or the other way round (1). The host alternates so that
//   the last pass writes the keys.
#include "include/select_common.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 10, std430) buffer SpareBlock { uvec4 spare[]; };

uvec4 loadKey(bool fromSpare, uint i) {
  if (fromSpare) return spare[i];
  return push.stage.z == 0u ? order[i] : relevance[i];
}
void storeKey(bool toSpare, uint i, uvec4 v) {
  if (toSpare) spare[i] = v;
  else if (push.stage.z == 0u) order[i] = v;
  else relevance[i] = v;
}

// Compare-exchange: a gets the smaller key.
#define RB_CSWAP(a, b)            \
  if (keyLess(b, a)) {            \
    uvec4 t = a;                  \
    a = b;                        \
    b = t;                        \
  }

// Sorts the invocation's chunk of 8 keys with a 19-comparator network on registers (no
// array indexed at run time: lavapipe would spill it; an insertion sort cost 4x more).
// Missing keys past n are all ones, sorted last and not stored.
void sortChunk(uint chunk, uint n, bool toSpare) {
  uint first = chunk * RB_MERGE_CHUNK;
  if (first >= n) return;
  uvec4 none = uvec4(0xFFFFFFFFu);
  uvec4 k0 = loadKey(false, first), k1 = first + 1u < n ? loadKey(false, first + 1u) : none;
  uvec4 k2 = first + 2u < n ? loadKey(false, first + 2u) : none, k3 = first + 3u < n ? loadKey(false, first + 3u) : none;
  uvec4 k4 = first + 4u < n ? loadKey(false, first + 4u) : none, k5 = first + 5u < n ? loadKey(false, first + 5u) : none;
  uvec4 k6 = first + 6u < n ? loadKey(false, first + 6u) : none, k7 = first + 7u < n ? loadKey(false, first + 7u) : none;
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
  uint n = candidateCount(), run = push.stage.x, first = gl_GlobalInvocationID.x * RB_MERGE_CHUNK;
  bool fromSpare = push.stage.y != 0u;
  if (run == 0u) {
    sortChunk(gl_GlobalInvocationID.x, n, fromSpare);
    return;
  }
  if (first >= n) return;
  // The two runs [a0, b0) and [b0, end) whose merge holds this invocation's outputs (a
  // chunk never straddles two pairs: runs are chunk multiples).
  uint a0 = (first / (2u * run)) * (2u * run), b0 = min(a0 + run, n), end = min(a0 + 2u * run, n);
  uint sizeA = b0 - a0, sizeB = end - b0, d = first - a0;
  // Merge path: how many of the first d outputs come from the first run.
  uint lo = d > sizeB ? d - sizeB : 0u, hi = min(d, sizeA);
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (keyLess(loadKey(fromSpare, a0 + mid), loadKey(fromSpare, b0 + d - mid - 1u))) lo = mid + 1u;
    else hi = mid;
  }
  uint a = a0 + lo, b = b0 + d - lo;
  uvec4 keyA = a < b0 ? loadKey(fromSpare, a) : uvec4(0u), keyB = b < end ? loadKey(fromSpare, b) : uvec4(0u);
  uint last = min(first + RB_MERGE_CHUNK, end);
  // Branch-free steps: one store and at most one load each, whichever run is taken.
  for (uint o = first; o < last; ++o) {
    bool takeA = b >= end || (a < b0 && keyLess(keyA, keyB));
    storeKey(!fromSpare, o, takeA ? keyA : keyB);
    a += takeA ? 1u : 0u;
    b += takeA ? 0u : 1u;
    uint next = takeA ? a : b;
    uvec4 v = next < (takeA ? b0 : end) ? loadKey(fromSpare, next) : uvec4(0u);
    keyA = takeA ? v : keyA;
    keyB = takeA ? keyB : v;
  }
}
