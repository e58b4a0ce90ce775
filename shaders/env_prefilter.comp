#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/brdf.glsl"
#include "include/sky.glsl"
#define RB_PREFILTER_SOURCE(dir, lod) textureLod(skyMap, dir, lod).rgb
#include "include/prefilter.glsl"

// The sky GGX-prefiltered (include/prefilter.glsl) into roughness level push.objectMaterial.x.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

void main() {
  uint mip = push.objectMaterial.x;
  uint size = max(RB_ENV_SIZE >> mip, 1u);
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= size || id.y >= size) return;
  imageStore(envStorage[mip], ivec3(id), vec4(prefilterTexel(cubeDirection(id.z, id.xy, size), mip), 1.0));
}
