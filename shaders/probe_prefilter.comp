#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/brdf.glsl"
#include "include/sky.glsl"
layout(push_constant) uniform PushBlock { DrawPush push; };
#define RB_PREFILTER_SOURCE(dir, lod) textureLod(probeRadiance, vec4(dir, float(push.objectMaterial.y)), lod).rgb
#include "include/prefilter.glsl"

// Reflection probe push.objectMaterial.y GGX-prefiltered (include/prefilter.glsl) into
// roughness level push.objectMaterial.x. Alpha: the share of the probe's directions that
// see the outside of a surface in the clear (the capture's alpha averaged by its 1x1 mip),
// below RB_PROBE_MIN_OUTSIDE when the probe's centre lies inside a closed object or against a
// surface; the probe is not used then (include/environment.glsl).
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

void main() {
  uint mip = push.objectMaterial.x, probe = push.objectMaterial.y;
  uint size = max(RB_ENV_SIZE >> mip, 1u);
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= size || id.y >= size) return;
  float outside = 0.0;
  const vec3 axes[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));
  for (int f = 0; f < 6; ++f) outside += textureLod(probeRadiance, vec4(axes[f], float(probe)), float(RB_PROBE_RADIANCE_MIPS - 1)).a;
  vec3 radiance = prefilterTexel(cubeDirection(id.z, id.xy, size), mip);
  imageStore(reflectionProbeMips[mip], ivec3(id.xy, probe * 6u + id.z), vec4(radiance, outside / 6.0));
}
