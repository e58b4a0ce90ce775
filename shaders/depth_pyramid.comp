#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/depth_pyramid.glsl"

// One level of the min-depth pyramid the screen-space reflections march in (Hi-Z): level L >= 1
// holds the nearest depth of the level L-1 texels it covers (three along an odd edge, so that
// no texel is left out), level 0 being the G-buffer's depth, which the march reads directly
// (a copy of it cost a full-resolution pass): the pyramid image's mip L - 1. push.objectMaterial.x = L.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

void main() {
  uint level = push.objectMaterial.x;
  ivec2 size = max(ivec2(frame.sizeLightsFrame.xy) >> level, ivec2(1));
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, size))) return;
  ivec2 below = max(ivec2(frame.sizeLightsFrame.xy) >> (level - 1u), ivec2(1));
  ivec2 reach = ivec2(2) + ivec2(equal(below & 1, ivec2(1))) * ivec2(equal(texel, size - 1));
  float nearest = 1.0;
  for (int y = 0; y < reach.y; ++y)
    for (int x = 0; x < reach.x; ++x) {
      ivec2 at = min(texel * 2 + ivec2(x, y), below - 1);
      nearest = min(nearest, pyramidDepth(at, int(level) - 1));
    }
  imageStore(depthPyramidLevels[level - 1u], texel, vec4(nearest));
}
