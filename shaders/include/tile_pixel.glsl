// Compute passes dispatched over the tile list (the trace passes). The includer
// includes bindings.glsl.
#ifndef RB_TILE_PIXEL_GLSL
#define RB_TILE_PIXEL_GLSL
#include "include/rates.glsl"

// This invocation's pixel: one workgroup per listed 8x8 tile. With reduced ray rates in the
// frame (RB_RT_RATES) the tile's pixels are handed out so that those a rate traces this frame
// come first: invocations 0-3 get the pixels 1/16 traces (one per 4x4 block), 0-15 those 1/4
// traces (one per 2x2 quad), 16-31 the rest of those 1/2 traces, 32-63 the others. A SIMD batch or warp holding only pixels its items
// skip then has nothing to do, where in row order every one would hold some pixels to trace
// (a checkerboard leaves half of each row).
ivec2 tilePixel(uint list) {
  uint t = tiles[list + gl_WorkGroupID.x];
  ivec2 origin = ivec2(t & 0xFFFFu, t >> 16) * RB_TILE_SIZE;
  if ((frame.rayTracing.w & RB_RT_RATES) == 0u) return origin + ivec2(gl_LocalInvocationID.xy);
  uint i = gl_LocalInvocationIndex, group = i >> 4u, k = i & 15u;
  // The 2x2 quad's top left in the tile: k's low bits the 4x4 block, its high bits the quad in
  // the block, counted from the one 1/16 traces (sixteenthOffset).
  uint block = k & 3u, inBlock = k >> 2u;
  uvec2 quad = (uvec2(block & 1u, block >> 1u) * 2u + (uvec2(inBlock & 1u, inBlock >> 1u) ^ quarterOffset(frame.sizeLightsFrame.w >> 2u))) * 2u;
  uvec2 q = quarterOffset(frame.sizeLightsFrame.w);
  // The quad's pixel of x + y's parity other than q is 1/2's other one; the last two are left.
  uvec2 offset = group == 0u ? q : (group == 1u ? uvec2(1u) - q : (group == 2u ? uvec2(q.x ^ 1u, q.y) : uvec2(q.x, q.y ^ 1u)));
  return origin + ivec2(quad + offset);
}

#endif
