#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"

// One level of the min-depth pyramid the screen-space reflections march in (Hi-Z): level 0
// copies the G-buffer's depth, level L holds the nearest depth of the level L-1 texels it
// covers (three along an odd edge, so that no texel is left out). push.objectMaterial.x = L.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

void main() {
  uint level = push.objectMaterial.x;
  ivec2 size = max(ivec2(frame.sizeLightsFrame.xy) >> level, ivec2(1));
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, size))) return;
  float nearest;
  if (level == 0u) {
    nearest = texelFetch(gDepth, texel, 0).r;
  } else {
    ivec2 below = max(ivec2(frame.sizeLightsFrame.xy) >> (level - 1u), ivec2(1));
    ivec2 reach = ivec2(2) + ivec2(equal(below & 1, ivec2(1))) * ivec2(equal(texel, size - 1));
    nearest = 1.0;
    for (int y = 0; y < reach.y; ++y)
      for (int x = 0; x < reach.x; ++x) nearest = min(nearest, texelFetch(depthPyramid, min(texel * 2 + ivec2(x, y), below - 1), int(level) - 1).r);
  }
  imageStore(depthPyramidLevels[level], texel, vec4(nearest));
}
