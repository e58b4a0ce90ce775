#version 460
#extension GL_GOOGLE_include_directive : require
// Sort keys of each candidate for the policy's order (ascending = selection order), and
// padding (all ones, sorted last) up to the power-of-two size the bitonic sort needs.
#include "include/select_common.glsl"

layout(local_size_x = 256) in;

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

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.sizes.y) return;
  uvec4 key = uvec4(0xFFFFFFFFu);
  if (i < candidateCount()) {
    GpuCandidate c = candidates[i];
    uint policy = push.sizes.z;
    if (policy == RB_SELECT_DENSITY) {
      precise float density = c.cost > 0.0 ? c.value / c.cost : uintBitsToFloat(0x7F800000u);
      key = uvec4(~orderedBits(density), orderedBits(c.cost), c.id, i);
    } else if (policy == RB_SELECT_NEAREST) {
      key = uvec4(orderedBits(c.distance), c.id, 0u, i);
    } else if (policy == RB_SELECT_RANDOM) {
      key = uvec4(randomRank(push.sizes.w, c.id), c.id, 0u, i);
    } else if (push.stage.z == 0u) {  // `paper`: the cost chain, most costly first
      key = uvec4(~orderedBits(c.cost), c.id, 0u, i);
    } else {  // `paper`: the relevance order, most relevant first
      key = uvec4(~orderedBits(c.value), c.id, 0u, i);
    }
  }
  if (push.stage.z == 0u) order[i] = key;
  else relevance[i] = key;
}
