// Shared by the GPU selection shaders (shaders/select/select_*.comp): their own descriptor set
// (engine/src/passes/gpu_selector.h) and push constants. The CPU reference is
// engine/src/select/policies.cpp; these shaders reproduce it exactly.
#ifndef RB_SELECT_COMMON_GLSL
#define RB_SELECT_COMMON_GLSL
#include "shared/random_rank.h"
#include "shared/selection.h"

layout(set = 0, binding = 0, std430) buffer CandidateBlock { GpuCandidate candidates[]; };
layout(set = 0, binding = 1, std430) buffer OrderBlock { uvec4 order[]; };       // sort keys k0, k1, k2, candidate index
layout(set = 0, binding = 2, std430) buffer RelevanceBlock { uvec4 relevance[]; };  // `paper`: the relevance order
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

bool keyLess(uvec4 a, uvec4 b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  if (a.z != b.z) return a.z < b.z;
  return a.w < b.w;
}

// The sort key of candidate i for the policy's order (which = 0) or `paper`'s relevance
// order (1): ascending = selection order; the candidate index is the last word, so keys
// are unique. Past the candidates: all ones, sorted last.
uvec4 candidateKey(uint i, uint which) {
  if (i >= candidateCount()) return uvec4(0xFFFFFFFFu);
  GpuCandidate c = candidates[i];
  uint policy = push.sizes.z;
  if (policy == RB_SELECT_DENSITY) {
    precise float density = c.cost > 0.0 ? c.value / c.cost : uintBitsToFloat(0x7F800000u);
    return uvec4(~orderedBits(density), orderedBits(c.cost), c.id, i);
  }
  if (policy == RB_SELECT_NEAREST) return uvec4(orderedBits(c.distance), c.id, 0u, i);
  if (policy == RB_SELECT_RANDOM) return uvec4(randomRank(push.sizes.w, c.id), c.id, 0u, i);
  if (which == 0u) return uvec4(~orderedBits(c.cost), c.id, 0u, i);  // `paper`: the cost chain, most costly first
  return uvec4(~orderedBits(c.value), c.id, 0u, i);                  // `paper`: the relevance order, most relevant first
}

#endif
