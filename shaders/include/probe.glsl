// The sparse probe of `benefit` (shared/selection.h): which 8x8 tiles it traces this frame,
// and whether a pixel's item is probed there. The includer includes bindings.glsl.
#ifndef RB_PROBE_GLSL
#define RB_PROBE_GLSL

// The frame's probe stride (0: no probe), kept in the items' totals record.
uint probeStride() { return itemCosts[itemTotalsIndex()].pixels; }

// A tile's place in the probe's rotation: a hash, so that the tiles probed together are
// spread over the screen rather than in rows.
uint tileTurn(uvec2 tile) {
  uint h = (tile.x * 0x8DA6B343u) ^ (tile.y * 0xD8163841u);
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  return h;
}

// Whether the probe traces `tile` this frame: each tile once every `stride` frames.
bool probeTile(uvec2 tile) {
  uint stride = probeStride();
  return stride != 0u && (tileTurn(tile) % stride + frame.sizeLightsFrame.w % stride) % stride == 0u;
}

// Whether the pixel's item `effect` is left out by the selection but probed here this frame.
bool itemProbed(Selection sel, uint effect, ivec2 pixel) {
  return (sel.word & (1u << (RB_PROBE_SHIFT + effect))) != 0u && probeTile(uvec2(pixel) / RB_TILE_SIZE);
}

#endif
