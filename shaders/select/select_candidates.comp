#version 460
#extension GL_GOOGLE_include_directive : require
// Frame mode: first each object's learned work per pixel takes in what the trace passes
// counted for it last frame (when it was traced; the native tracer counts nothing, so its
// objects keep the prior), and the counter restarts. Then every candidate object (visible,
// something to trace, R > 0) becomes a selection candidate with its predicted cost, kappa
// times its work: the paper's C for `paper`; for the other policies its pixels times its
// work per pixel (Q times a prior per ray until measured).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "include/select_common.glsl"

layout(local_size_x = 64) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.walk.z) return;
  selected[i] = 0u;  // until the walk selects it
  GpuObjectCost oc = costs[i];
  // engine/src/select/cost_model.cpp is the CPU reference of these lines, equal bit for bit.
  if (oc.pixels > 0u && oc.work > 0u) {
    float observed = exactQuotient(float(oc.work), float(oc.pixels));
    oc.workPerPixel = oc.workPerPixel > 0.0 ? 0.5 * (oc.workPerPixel + observed) : observed;
  }
  costs[i] = GpuObjectCost(oc.workPerPixel, 0u, 0u, 0u);
  GpuObjectRecord r = records[i];
  if (r.crCandidatePixels.z < 0.5) return;
  float pixels = float(floatBitsToUint(r.crCandidatePixels.w));
  float perPixel = oc.workPerPixel > 0.0 ? oc.workPerPixel : params[i].kqiS.y * float(RB_PRIOR_WORK_PER_RAY);
  float work = push.sizes.z == RB_SELECT_PAPER ? r.crCandidatePixels.x : pixels * perPixel;
  float cost = push.budget.y * work;
  uint slot = atomicAdd(result.x, 1u);
  candidates[slot] = GpuCandidate(i, cost, r.crCandidatePixels.y, r.apdv.z);
  slotOf[i] = slot;
  // The candidates' total cost for allCandidatesFit (select_common.glsl): in units of
  // 2^-20 budget rounded up, one lane at most 2^21 (anything above one budget fails anyway),
  // summed per subgroup, then into 64 bits (lo, hi) with an explicit carry.
  float u = ceil(cost / push.budget.x * 1048576.0);
  uint units = u <= 2097152.0 ? uint(u) : 2097152u;  // NaN compares false: the cap
  uint sum = subgroupAdd(units);
  if (subgroupElect()) {
    uint old = atomicAdd(result2.y, sum);
    if (old + sum < old) atomicAdd(result2.z, 1u);
  }
}
