#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "include/rt_common.glsl"
#include "include/environment.glsl"
#include "include/sky.glsl"
#include "include/trace_radiance.glsl"

// Captures reflection probe push.objectMaterial.x: the radiance arriving at its centre
// through every texel of its cube (one invocation per texel, z the face), traced and
// shaded as a traced reflection's first hit is (trace_radiance.glsl), so that the probe
// and the rays it stands in for agree where the probe's centre sees what the surface
// would. Alpha 0 where the ray meets the back of a one-sided surface (the centre is inside a
// closed object) or a surface nearer than RB_PROBE_MIN_CLEARANCE of the scene's diagonal (the
// centre is against it, and would show that surface for most of what it stands for); the
// prefilter counts them (probe_prefilter.comp).
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

void main() {
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= RB_ENV_SIZE || id.y >= RB_ENV_SIZE) return;
  uint probe = push.objectMaterial.x;
  uint face = push.objectMaterial.y + id.z;  // the dispatch's first face, then one per z
  vec3 dir = cubeDirection(face, id.xy, RB_ENV_SIZE);
  uint work = 0u;
  vec3 radiance = traceRadiance(frame.probeCenter[probe].xyz, dir, 0.0, 1u, work);
  bool against = rbFirstHitDistance < RB_PROBE_MIN_CLEARANCE * frame.ssr.z;
  imageStore(probeRadianceImage, ivec3(id.xy, probe * 6u + face), vec4(radiance, rbFirstHitInside || against ? 0.0 : 1.0));
}
