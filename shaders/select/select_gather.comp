#version 460
#extension GL_GOOGLE_include_directive : require
// The walk's input laid out as consecutive records, so its one subgroup reads each batch with
// one load whose address it knows, instead of a chain of dependent loads per batch
// (position, slot, candidate). On a GPU that chain, not the decisions, was most of the walk.
// - greedy policies: the policy's order, per position (cost, value, slot, ID); the walk
//   loads the next batch while it decides the current one.
// - `paper`: the cost chain at [0, n) and the relevance order at [padded, padded + n), per
//   position (cost, slot, pointer window, value): the window is where the node's
//   higher-relevance pointers end, the first position of its group of equal relevance
//   (found by binary search in the relevance order), and they start N before it.
#include "shared/config.h"
#include "include/select_common.glsl"

layout(local_size_x = RB_GROUP_SIZE) in;

// The first position in the relevance order whose key's first word is `word` (sorted
// ascending: most relevant first, equal relevance together).
uint groupStart(uint word, uint n) {
  uint lo = 0u, hi = n;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (relevance[mid].x < word) lo = mid + 1u;
    else hi = mid;
  }
  return lo;
}

uvec4 paperRecord(uint ci, uint n) {
  GpuCandidate c = candidates[ci];
  return uvec4(floatBitsToUint(c.cost), ci, groupStart(~orderedBits(c.value), n), floatBitsToUint(c.value));
}

void main() {
  uint i = gl_GlobalInvocationID.x, n = candidateCount();
  if (i >= n || allCandidatesFit()) return;  // all fit: the walk reads no order
  uint ci = candidateAt(order[i].y);
  if (push.sizes.z == RB_SELECT_PAPER) {
    walkOrder[i] = paperRecord(ci, n);
    walkOrder[push.sizes.y + i] = paperRecord(candidateAt(relevance[i].y), n);
    return;
  }
  walkOrder[i] = greedyRecord(ci);
}
