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

// `benefit`'s partial item (shared/selection.h): an object's selection word at `tile`, the
// partial item's bits (selected, rate) cleared where the tile is not among its traced share.
uint selectionInTile(uint objectId, uint word, uvec2 tile) {
  uint partial = itemCosts[itemTotalsIndex()].selectedLast;
  if (partial == 0u || (partial - 1u) / RB_ITEMS_PER_OBJECT != objectId) return word;
  if (float(tileTurn(tile) >> 8u) * (1.0 / 16777216.0) < itemCosts[itemTotalsIndex()].benefit) return word;
  uint effect = (partial - 1u) % RB_ITEMS_PER_OBJECT;
  return word & ~((1u << effect) | (3u << (RB_RATE_SHIFT + 2u * effect)));
}

// An object's selection at a pixel: what the trace and lighting passes act on.
Selection selectionAt(uint objectId, ivec2 pixel) {
  Selection sel = selectionOf(objectId);
  if (objectId != RB_NO_OBJECT) sel.word = selectionInTile(objectId, sel.word, uvec2(pixel) / RB_TILE_SIZE);
  return sel;
}

#endif
