#version 460
#extension GL_GOOGLE_include_directive : require
// Batch tracer: one ray per invocation from a buffer, closest hit or any hit (push flags),
// every candidate accepted. Used by the oracle tests and the throughput benchmark.
#define RB_BVH_SET 0
#define RB_BVH_BINDING 0
#include "shared/config.h"
#include "include/rayquery.glsl"

layout(local_size_x = RB_GROUP_SIZE) in;
layout(set = 0, binding = 3, std430) readonly buffer RayBlock { GpuRay rays[]; };
layout(set = 0, binding = 4, std430) writeonly buffer HitBlock { GpuHit hits[]; };
layout(push_constant) uniform PushBlock {
  uint count;
  uint flags;
} push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  GpuRay r = rays[i];
  RayQuery q;
  rqInitialize(q, push.flags, 0xFFu, r.originTMin.xyz, r.originTMin.w, r.dirTMax.xyz, r.dirTMax.w);
  while (rqProceed(q)) rqConfirm(q);
  GpuHit h;
  bool hit = rqCommittedHit(q);
  uvec2 work = rqWork(q);
  h.t = hit ? rqCommittedT(q) : r.dirTMax.w;
  h.object = hit ? rqCommittedObject(q) : 0u;
  h.primitive = hit ? rqCommittedPrimitive(q) : 0u;
  h.flags = hit ? (1u | (rqCommittedFrontFace(q) ? 2u : 0u)) : 0u;
  h.baryWork = vec4(hit ? rqCommittedBarycentrics(q) : vec2(0.0), float(work.x), float(work.y));
  hits[i] = h;
}
