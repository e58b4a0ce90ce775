#version 460
#extension GL_GOOGLE_include_directive : require
// Appends each 8x8 tile holding at least one pixel whose shadow item is selected, or probed
// where the probe traces this frame (include/probe.glsl), to the shadow pass's tile list, and
// each holding one with a selected or probed reflection or refraction item to the other
// pass's; each list's count is also the x of its pass's indirect dispatch: no selected pixel,
// no work.
// One invocation per tile: it checks the few objects the coverage pass noted for the tile,
// and scans the tile's pixels only when the tile shows more (fetching every pixel cost
// ~0.35 ms at 640x360 on lavapipe, most of the select pass for a small scene). No shared
// memory and no barrier (a per-pixel workgroup with two barriers cost ~2 ms, where a
// workgroup barrier switches between invocations in software).
#include "include/bindings.glsl"
#include "include/probe.glsl"

layout(local_size_x = RB_GROUP_SIZE) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

void main() {
  uint t = gl_GlobalInvocationID.x;
  uvec2 first, last;
  if (!screenTile(t, first, last)) return;
  uvec2 tile = first / RB_TILE_SIZE;
  uint base = t * RB_TILE_OBJECT_WORDS;
  // The selection bits that make a pixel of this tile traced by each pass: its items', and its
  // probed items' where the probe traces this tile.
  uint items = RB_ITEMS_ALL | (probeTile(tile) ? RB_ITEMS_ALL << RB_PROBE_SHIFT : 0u);
  uint shadows = (1u << RB_ITEM_SHADOWS) | (1u << (RB_PROBE_SHIFT + RB_ITEM_SHADOWS));
  uint bits = 0u;  // the selection bits of the tile's pixels that either pass traces
  if (tileObjects[base + RB_TILE_OBJECT_WORDS - 1u] == 0u) {
    for (uint s = 0u; s + 1u < RB_TILE_OBJECT_WORDS; ++s) {
      uint v = tileObjects[base + s];
      if (v != 0u) bits |= selectionInTile(v - 1u, selected[v - 1u], tile) & items;
    }
  } else {
    for (uint y = first.y; y < last.y && (bits & items) != items; ++y)
      for (uint x = first.x; x < last.x; ++x) {
        uint id = texelFetch(gObjectId, ivec2(x, y), 0).r;
        if (id != RB_NO_OBJECT) bits |= selectionInTile(id, selected[id], tile) & items;
      }
  }
  uint tileWord = tile.x | (tile.y << 16);
  if ((bits & shadows) != 0u) tiles[RB_SHADOW_TILES + atomicAdd(tileDispatch.x, 1u)] = tileWord;
  if ((bits & ~shadows) != 0u) tiles[RB_EFFECT_TILES + atomicAdd(effectDispatch.x, 1u)] = tileWord;
  if (bits != 0u) atomicAdd(effectDispatch.w, 1u);
}
