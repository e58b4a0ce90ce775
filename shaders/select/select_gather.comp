#version 460
#extension GL_GOOGLE_include_directive : require
// The greedy walk's input: the policy's order laid out as consecutive records (cost, value,
// candidate slot, ID), so the walk's one subgroup reads each batch with one load whose
// address it knows ahead, the next batch's in flight while it decides the current one,
// instead of a chain of dependent loads per batch (position, slot, candidate). On a GPU
// that chain, not the decisions, was most of the walk.
#include "include/select_common.glsl"

layout(local_size_x = 64) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= candidateCount() || allCandidatesFit()) return;  // all fit: the walk reads no order
  uint ci = candidateAt(order[i].y);
  GpuCandidate c = candidates[ci];
  walkOrder[i] = uvec4(floatBitsToUint(c.cost), floatBitsToUint(c.value), ci, c.id);
}
