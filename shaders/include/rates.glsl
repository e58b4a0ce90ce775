// Ray rates (shared/selection.h): which pixels of a selected item are traced this frame. The
// includer includes bindings.glsl.
#ifndef RB_RATES_GLSL
#define RB_RATES_GLSL

// The rate of the pixel's item `effect` (RB_RATE_FULL where nothing is selected).
uint itemRate(Selection sel, uint effect) { return (sel.word >> (RB_RATE_SHIFT + 2u * effect)) & 3u; }

// The pixel of each 2x2 quad that 1/4 traces in frame `f`: top left, top right, bottom right,
// bottom left in turn. Its x + y has the parity of f, so it is one of the pixels 1/2 traces
// in the same frame (tile_pixel.glsl hands those out first).
uvec2 quarterOffset(uint f) {
  uint turn = f & 3u;
  return uvec2(turn == 1u || turn == 2u ? 1u : 0u, turn >= 2u ? 1u : 0u);
}

// The pixel of each 4x4 block that 1/16 traces in frame `f`: in the block's 2x2 quad
// quarterOffset(f / 4) the pixel quarterOffset(f), which 1/4 (and so 1/2) traces too; every
// pixel of the block once in 16 frames.
uvec2 sixteenthOffset(uint f) { return quarterOffset(f >> 2u) * 2u + quarterOffset(f); }

// Whether `rate` traces `pixel` this frame. 1/2: a checkerboard, the other half next frame;
// 1/4: one pixel of each 2x2 quad, a different one each frame; 1/16: one of each 4x4 block.
bool rateTraces(uint rate, ivec2 pixel) {
  uint f = frame.sizeLightsFrame.w;
  if (rate == RB_RATE_HALF) return ((uint(pixel.x + pixel.y) + f) & 1u) == 0u;
  if (rate == RB_RATE_QUARTER) return all(equal(uvec2(pixel & 1), quarterOffset(f)));
  if (rate == RB_RATE_SIXTEENTH) return all(equal(uvec2(pixel & 3), sixteenthOffset(f)));
  return true;
}

// The frames after which `rate` traces a pixel again.
uint ratePeriod(uint rate) { return RB_RATE_PERIOD(rate); }

// Whether the pixel's selected item `effect` is traced here this frame.
bool itemTracedHere(Selection sel, uint effect, ivec2 pixel) { return rateTraces(itemRate(sel, effect), pixel); }

#endif
