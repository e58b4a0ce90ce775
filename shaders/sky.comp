#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/sky.glsl"

// Writes the procedural sky into mip 0 of the sky cube map (one invocation per texel).
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

void main() {
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= RB_ENV_SIZE || id.y >= RB_ENV_SIZE) return;
  vec3 dir = cubeDirection(id.z, id.xy, RB_ENV_SIZE);
  imageStore(skyStorage, ivec3(id), vec4(skyRadiance(dir, frame.sunDirection.xyz, frame.sunDirection.w), 1.0));
}
