#version 460
#extension GL_GOOGLE_include_directive : require
// Appends each 8x8 tile holding at least one selected pixel, or a probed one where the probe
// traces this frame (include/probe.glsl), to the tile list, whose count is also the x of the
// trace passes' indirect dispatch: no selected pixel, no work.
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
  // The selection bits that make a pixel of this tile traced: its items', and its probed
  // items' where the probe traces this tile.
  uint traced = RB_ITEMS_ALL | (probeTile(tile) ? RB_ITEMS_ALL << RB_PROBE_SHIFT : 0u);
  bool any = false;
  if (tileObjects[base + RB_TILE_OBJECT_WORDS - 1u] == 0u) {
    for (uint s = 0u; s + 1u < RB_TILE_OBJECT_WORDS; ++s) {
      uint v = tileObjects[base + s];
      any = any || (v != 0u && (selected[v - 1u] & traced) != 0u);
    }
  } else {
    for (uint y = first.y; y < last.y && !any; ++y)
      for (uint x = first.x; x < last.x && !any; ++x) {
        uint id = texelFetch(gObjectId, ivec2(x, y), 0).r;
        any = any || (id != RB_NO_OBJECT && (selected[id] & traced) != 0u);
      }
  }
  if (any) tiles[atomicAdd(tileDispatch.x, 1u)] = tile.x | (tile.y << 16);
}
