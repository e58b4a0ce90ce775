#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/brdf.glsl"
#include "include/sky.glsl"

// Writes the sky into mip 0 of the sky cube map (one invocation per texel): the procedural
// sky, or with push.objectMaterial.x == 1 the equirectangular (lat-long) HDR image:
// u = atan(z, x) / 2pi + 0.5, v = acos(y) / pi, so the top row is the zenith (+y).
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

void main() {
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= RB_ENV_SIZE || id.y >= RB_ENV_SIZE) return;
  vec3 dir = cubeDirection(id.z, id.xy, RB_ENV_SIZE);
  vec3 radiance;
  if (push.objectMaterial.x == 1u) {
    vec2 uv = vec2(atan(dir.z, dir.x) / (2.0 * PI) + 0.5, acos(clamp(dir.y, -1.0, 1.0)) / PI);
    radiance = textureLod(envSource, uv, 0.0).rgb * frame.sunDirection.w;
  } else {
    radiance = skyRadiance(dir, frame.sunDirection.xyz, frame.sunDirection.w);
  }
  imageStore(skyStorage, ivec3(id), vec4(radiance, 1.0));
}
