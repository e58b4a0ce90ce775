#version 460
#extension GL_GOOGLE_include_directive : require
// Frame mode: every candidate object (visible, something to trace, R > 0) becomes a
// selection candidate with its predicted cost, kappa times its work: the paper's C for
// `paper`, its pixels times Q (the rays it will shoot) for the other policies.
#include "include/select_common.glsl"

layout(local_size_x = 64) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.walk.z) return;
  GpuObjectRecord r = records[i];
  if (r.crCandidatePixels.z < 0.5) return;
  float pixels = float(floatBitsToUint(r.crCandidatePixels.w));
  float work = push.sizes.z == RB_SELECT_PAPER ? r.crCandidatePixels.x : pixels * params[i].kqiS.y;
  uint slot = atomicAdd(result.x, 1u);
  candidates[slot] = GpuCandidate(i, push.budget.y * work, r.crCandidatePixels.y, r.apdv.z);
}
