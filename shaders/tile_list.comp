#version 460
#extension GL_GOOGLE_include_directive : require
// Appends each 8x8 tile holding at least one selected pixel to the tile list, whose count
// is also the x of the trace passes' indirect dispatch: no selected pixel, no work.
#include "include/bindings.glsl"

layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

shared uint anySelected;

void main() {
  if (gl_LocalInvocationIndex == 0u) anySelected = 0u;
  barrier();
  uvec2 p = gl_GlobalInvocationID.xy;
  if (all(lessThan(p, frame.sizeLightsFrame.xy)) && pixelSelected(texelFetch(gObjectId, ivec2(p), 0).r)) anySelected = 1u;
  barrier();
  if (gl_LocalInvocationIndex == 0u && anySelected != 0u) {
    uint slot = atomicAdd(tileDispatch.x, 1u);
    tiles[slot] = gl_WorkGroupID.x | (gl_WorkGroupID.y << 16);
  }
}
