// The pixels of the trace passes dispatched over the tile lists (tile_list.comp), over chunks
// of tiles. The includer includes bindings.glsl.
#ifndef RB_TILE_PIXEL_GLSL
#define RB_TILE_PIXEL_GLSL
#include "include/rates.glsl"

// A tile's pixels in rank order. Without reduced ray rates in the frame (RB_RT_RATES) row
// order. With them the pixels a rate traces this frame come first: ranks 0-3 the pixels 1/16
// traces (one per 4x4 block), 0-15 those 1/4 traces (one per 2x2 quad), 16-31 the rest of those
// 1/2 traces, 32-63 the others. A SIMD batch or warp holding only pixels its items skip then
// has nothing to do, where in row order every one would hold some pixels to trace (a
// checkerboard leaves half of each row).
ivec2 rankPixel(uvec2 tile, uint rank) {
  ivec2 origin = ivec2(tile) * RB_TILE_SIZE;
  if ((frame.rayTracing.w & RB_RT_RATES) == 0u) return origin + ivec2(rank % RB_TILE_SIZE, rank / RB_TILE_SIZE);
  uint group = rank >> 4u, k = rank & 15u;
  // The 2x2 quad's top left in the tile: k's low bits the 4x4 block, its high bits the quad in
  // the block, counted from the one 1/16 traces (sixteenthOffset).
  uint block = k & 3u, inBlock = k >> 2u;
  uvec2 quad = (uvec2(block & 1u, block >> 1u) * 2u + (uvec2(inBlock & 1u, inBlock >> 1u) ^ quarterOffset(frame.sizeLightsFrame.w >> 2u))) * 2u;
  uvec2 q = quarterOffset(frame.sizeLightsFrame.w);
  // The quad's pixel of x + y's parity other than q is 1/2's other one; the last two are left.
  uvec2 offset = group == 0u ? q : (group == 1u ? uvec2(1u) - q : (group == 2u ? uvec2(q.x ^ 1u, q.y) : uvec2(q.x, q.y ^ 1u)));
  return origin + ivec2(quad + offset);
}

// The ranks of a tile a trace pass runs for an item at `rate` (RB_RATE_*): a rate traces one
// pixel in its period's (rankPixel puts them first): 4 at 1/16, 16 at 1/4, 32 at 1/2, all 64 at
// full rate (and where a probe traces).
uint rateRanks(uint rate) { return RB_TILE_SIZE * RB_TILE_SIZE / ratePeriod(rate); }

// A chunk: RB_TRACE_CHUNK consecutive ranks of a tile, from rank 4c.
uint chunkWord(uvec2 tile, uint c) { return tile.x | (tile.y << 12u) | (c << 24u); }
uvec2 chunkTile(uint word) { return uvec2(word & 0xFFFu, (word >> 12u) & 0xFFFu); }

// The pixel of a trace pass over chunks (`list`: RB_SHADOW_CHUNKS or RB_EFFECT_CHUNKS),
// ivec2(-1) past the list's end. A trace pass's list holds a tile's chunks up to the ranks its
// items' rates trace, so invocations run only where some item may trace: a tile at 1/16 costs
// a trace pass 4, not 64, and two such tiles fill a SIMD batch of 8 lanes (over whole tiles,
// the 60 invocations that returned at once were most of the shadow pass at 1/16, and the four
// that traced left half of their batch idle). (The fill's list, RB_FILL_CHUNKS, holds one
// chunk a tile: fill_effects.comp runs an invocation per 4x4 block.)
ivec2 chunkPixel(uint list) {
  uint g = gl_GlobalInvocationID.x, chunk = g / RB_TRACE_CHUNK;
  uint count = list == RB_SHADOW_CHUNKS ? traceCounts.y : traceCounts.z;
  if (chunk >= count) return ivec2(-1);
  uint word = tiles[list + chunk];
  return rankPixel(chunkTile(word), (word >> 24u) * RB_TRACE_CHUNK + g % RB_TRACE_CHUNK);
}

#endif
