// Shared by the GPU selection shaders (shaders/select/select_*.comp): their own descriptor set
// (engine/src/passes/gpu_selector.h) and push constants. The CPU reference is
// engine/src/select/policies.cpp; these shaders reproduce it exactly.
#ifndef RB_SELECT_COMMON_GLSL
#define RB_SELECT_COMMON_GLSL
#include "shared/selection.h"

layout(set = 0, binding = 0, std430) buffer CandidateBlock { GpuCandidate candidates[]; };
// Sort keys: (the order's primary word, candidate index); see candidateKey.
layout(set = 0, binding = 1, std430) buffer OrderBlock { uvec2 order[]; };
layout(set = 0, binding = 2, std430) buffer RelevanceBlock { uvec2 relevance[]; };  // `paper`: the relevance order
layout(set = 0, binding = 3, std430) buffer ScratchBlock { uint scratch[]; };     // `paper`: taken, rank, group start
layout(set = 0, binding = 4, std430) buffer FlagBlock { uint selectedFlags[]; };  // per candidate: 1 selected
// Frame mode: x candidates, y predicted cost and z value (float bits), w selected; then
// x objects whose selection changed since the last frame.
layout(set = 0, binding = 5, std430) buffer ResultBlock { uvec4 result; uvec4 result2; };
// Frame mode: the renderer's per-object records, selection and K/Q/I/S (shared/selection.h).
layout(set = 0, binding = 6, std430) readonly buffer RecordBlock { GpuObjectRecord records[]; };
layout(set = 0, binding = 7, std430) buffer SelectedBlock { uint selected[]; };
layout(set = 0, binding = 8, std430) buffer ParamsBlock { GpuObjectParams params[]; };
layout(set = 0, binding = 9, std430) buffer CostBlock { GpuObjectCost costs[]; };

layout(push_constant) uniform SelectPush {
  uvec4 sizes;   // x candidates, y padded (power of two), z policy (RB_SELECT_*), w seed
  uvec4 stage;   // x bitonic k, y bitonic j, z which order (0 main, 1 relevance), w `paper` pointers N
  vec4 budget;   // x budget, y frame mode: kappa (budget units per unit of work)
  uvec4 walk;    // x `paper` pointer hops per pick (0: as many as fit), y 1: frame mode, z objects
} push;

// Candidates: given (push) or, in frame mode, counted on the GPU by select_candidates.comp.
uint candidateCount() { return push.walk.y != 0u ? result.x : push.sizes.x; }

// The part of the key array the sort must order: the candidates rounded up to a power of
// two (at least one 1024-key block). In frame mode the dispatches cover every object; the
// invocations beyond this size (usually most: only visible objects are candidates) exit.
uint sortSize() {
  uint n = max(candidateCount(), 1u);
  uint p = n == 1u ? 1u : 1u << uint(findMSB(n - 1u) + 1);
  return min(max(p, 1024u), push.sizes.y);
}

// Policies, as in select::Policy.
#define RB_SELECT_NONE 0u
#define RB_SELECT_ALL 1u
#define RB_SELECT_PAPER 2u
#define RB_SELECT_DENSITY 3u
#define RB_SELECT_NEAREST 5u
#define RB_SELECT_RANDOM 6u

// Float bits mapped so that unsigned order is float order (ascending).
uint orderedBits(float f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}

// lowbias32 of (seed, ID): the order of `random` (select::randomRank).
uint randomRank(uint seed, uint id) {
  uint x = id ^ (seed * 0x9E3779B9u);
  x ^= x >> 16;
  x *= 0x7FEB352Du;
  x ^= x >> 15;
  x *= 0x846CA68Bu;
  x ^= x >> 16;
  return x;
}

// The sort key of candidate i for the policy's order (which = 0) or `paper`'s relevance
// order (1), ascending = selection order: the order's first criterion as ordered bits and
// the candidate index. Keys are two words, not all criteria, because on a CPU device the
// sort's time is its memory traffic; the rare ties in the first word are broken by
// keyLess from the candidates. Past the candidates: all ones and the index, sorted last.
uvec2 candidateKey(uint i, uint which) {
  if (i >= candidateCount()) return uvec2(0xFFFFFFFFu, i);
  GpuCandidate c = candidates[i];
  uint policy = push.sizes.z;
  if (policy == RB_SELECT_DENSITY) {
    precise float density = c.cost > 0.0 ? c.value / c.cost : uintBitsToFloat(0x7F800000u);
    return uvec2(~orderedBits(density), i);
  }
  if (policy == RB_SELECT_NEAREST) return uvec2(orderedBits(c.distance), i);
  if (policy == RB_SELECT_RANDOM) return uvec2(randomRank(push.sizes.w, c.id), i);
  if (which == 0u) return uvec2(~orderedBits(c.cost), i);  // `paper`: the cost chain, most costly first
  return uvec2(~orderedBits(c.value), i);                  // `paper`: the relevance order, most relevant first
}

// Candidates i and j tie in the first word: density then by lower cost, every order then
// by lower ID, then lower index (select::policies' order). Past the candidates: last.
bool tieLess(uint i, uint j) {
  uint n = candidateCount();
  if (i >= n || j >= n) return i < j;
  GpuCandidate a = candidates[i], b = candidates[j];
  if (push.sizes.z == RB_SELECT_DENSITY && a.cost != b.cost) return orderedBits(a.cost) < orderedBits(b.cost);
  if (a.id != b.id) return a.id < b.id;
  return i < j;
}

bool keyLess(uvec2 a, uvec2 b) { return a.x != b.x ? a.x < b.x : tieLess(a.y, b.y); }

#endif
