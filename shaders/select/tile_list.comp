#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_realtime_clock : require
// Lists, for each trace pass, the chunks of the 8x8 tiles where it may trace (include/tile_pixel.glsl):
// a tile holding a pixel whose shadow item is selected, or probed where the probe traces this
// frame (include/probe.glsl), goes to the shadow pass's list with as many of its chunks as the
// highest ray rate among those items traces (all 16 at full rate or probed, 8 at 1/2, 4 at 1/4,
// 1 at 1/16); one holding a selected or probed reflection or refraction item, to the other
// pass's; and one holding a reflection or refraction item at a reduced rate, to the fill's as
// one chunk (fill_effects.comp's invocation per 4x4 block). Each list's count sets its pass's
// indirect dispatch: no selected pixel, no work.
// One invocation per tile: it checks the few objects the coverage pass noted for the tile,
// and scans the tile's pixels only when the tile shows more (fetching every pixel cost
// ~0.35 ms at 640x360 on lavapipe, most of the select pass for a small scene). No shared
// memory and no barrier (a per-pixel workgroup with two barriers cost ~2 ms, where a
// workgroup barrier switches between invocations in software).
#include "include/bindings.glsl"
#include "include/probe.glsl"
#include "include/tile_pixel.glsl"
#include "include/stage_clock.glsl"

layout(local_size_x = RB_GROUP_SIZE) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

// The ranks of the tile a trace pass needs for an object whose selection word here is `word`
// (selectionInTile), over its items `effects` (bits); `probed`: the probe traces this tile.
uint tracedRanks(uint word, uint effects, bool probed) {
  uint ranks = 0u;
  for (uint e = 0u; e < RB_ITEMS_PER_OBJECT; ++e) {
    if ((effects & (1u << e)) == 0u) continue;
    if ((word & (1u << e)) != 0u) ranks = max(ranks, rateRanks((word >> (RB_RATE_SHIFT + 2u * e)) & 3u));
    else if (probed && (word & (1u << (RB_PROBE_SHIFT + e))) != 0u) ranks = RB_TILE_SIZE * RB_TILE_SIZE;
  }
  return ranks;
}

// Whether a selected item in `effects` of an object with selection word `word` has a reduced
// rate, which skips pixels the fill fills.
bool skipsPixels(uint word, uint effects) {
  for (uint e = 0u; e < RB_ITEMS_PER_OBJECT; ++e)
    if ((effects & word & (1u << e)) != 0u && ((word >> (RB_RATE_SHIFT + 2u * e)) & 3u) != RB_RATE_FULL) return true;
  return false;
}

// Adds an object whose selection word at this tile is `word` (selectionInTile) to the ranks the
// shadow pass (x) and the effect pass (y) trace, and to whether the fill runs over the tile.
void addObject(inout uvec2 ranks, inout bool fill, uint word, bool probed) {
  const uint shadows = 1u << RB_ITEM_SHADOWS, effects = RB_ITEMS_ALL & ~shadows;
  ranks = max(ranks, uvec2(tracedRanks(word, shadows, probed), tracedRanks(word, effects, probed)));
  fill = fill || skipsPixels(word, effects);
}

// Appends the tile's chunks [first, end) to the list at `list` whose count was `at` before.
void writeChunks(uint list, uint at, uvec2 tile, uint first, uint end) {
  for (uint c = first; c < end; ++c) tiles[list + at + c - first] = chunkWord(tile, c);
}

// The workgroups that `chunks` listed chunks need.
uint chunkGroups(uint chunks) { return (chunks * RB_TRACE_CHUNK + RB_TRACE_GROUP_SIZE - 1u) / RB_TRACE_GROUP_SIZE; }

void listTile() {
  uint t = gl_GlobalInvocationID.x;
  uvec2 first, last;
  if (!screenTile(t, first, last)) return;
  uvec2 tile = first / RB_TILE_SIZE;
  uint base = t * RB_TILE_OBJECT_WORDS;
  bool probed = probeTile(tile);
  // The ranks the shadow pass and the effect pass trace, and whether the fill runs.
  uvec2 ranks = uvec2(0u);
  bool fill = false;
  if (tileObjects[base + RB_TILE_OBJECT_WORDS - 1u] == 0u) {
    for (uint s = 0u; s + 1u < RB_TILE_OBJECT_WORDS; ++s) {
      uint v = tileObjects[base + s];
      if (v == 0u) continue;
      addObject(ranks, fill, selectionInTile(v - 1u, selected[v - 1u], tile), probed);
    }
  } else {
    for (uint y = first.y; y < last.y; ++y)
      for (uint x = first.x; x < last.x; ++x) {
        uint id = texelFetch(gObjectId, ivec2(x, y), 0).r;
        if (id == RB_NO_OBJECT) continue;
        addObject(ranks, fill, selectionInTile(id, selected[id], tile), probed);
      }
  }
  if (ranks.x != 0u) {
    uint chunks = ranks.x / RB_TRACE_CHUNK, at = atomicAdd(traceCounts.y, chunks);
    writeChunks(RB_SHADOW_CHUNKS, at, tile, 0u, chunks);
    atomicAdd(tileDispatch.x, chunkGroups(at + chunks) - chunkGroups(at));
    atomicAdd(tileCounts.x, 1u);
  }
  if (ranks.y != 0u) {
    uint chunks = ranks.y / RB_TRACE_CHUNK, at = atomicAdd(traceCounts.z, chunks);
    writeChunks(RB_EFFECT_CHUNKS, at, tile, 0u, chunks);
    atomicAdd(effectDispatch.x, chunkGroups(at + chunks) - chunkGroups(at));
    atomicAdd(tileCounts.y, 1u);
  }
  if (fill) {  // one chunk: the fill's invocation per 4x4 block
    uint at = atomicAdd(traceCounts.w, 1u);
    tiles[RB_FILL_CHUNKS + at] = chunkWord(tile, 0u);
    atomicAdd(fillDispatch.x, chunkGroups(at + 1u) - chunkGroups(at));
  }
  if (any(notEqual(ranks, uvec2(0u)))) atomicAdd(effectDispatch.w, 1u);
}

void main() {
  listTile();
  stampStageSpan();  // the select pass ends
}
