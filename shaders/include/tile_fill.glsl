// The fill of reduced ray rates (include/rates.glsl) for reflections and refractions, inside
// the effects pass: after the pixels a rate traces this frame have traced, each shares what it
// traced in the workgroup's shared memory, the workgroup waits at a barrier, and every pixel
// its item skipped this frame takes the weighted mean of the values traced around it
// (fillOffset) in the same 8x8 tile on the same object, weighted as include/fill_weights.glsl
// says. For 1/2 and 1/4 the 3x3 pixels around it, which always hold its own 2x2 quad (1/4
// traces one pixel of it, 1/2 two); for 1/16 the tile's four pixels it traced, one per 4x4
// block, up to three pixels away on each axis. Neighbours across the tile's edge are left out
// (a pass of its own reading them from images cost as much as the tracing it saved on
// lavapipe). Where no neighbour qualifies the fallback stays. The includer includes
// bindings.glsl. (Shadows fill in the lighting pass: include/shadow_fill.glsl.)
#ifndef RB_TILE_FILL_GLSL
#define RB_TILE_FILL_GLSL
#include "include/fill_weights.glsl"

#define RB_TILE_PIXELS (RB_TILE_SIZE * RB_TILE_SIZE)

// Per pixel of the tile: the object it traced for (RB_NO_OBJECT: nothing to share), where;
// the last four slots copy the pixels 1/16 traces, one per 4x4 block (sixteenthSample).
#define RB_FILL_SLOTS (RB_TILE_PIXELS + 4)
shared uint fillObject[RB_FILL_SLOTS];
shared vec3 fillPosition[RB_FILL_SLOTS];
shared vec3 fillNormal[RB_FILL_SLOTS];

// Whether the trace passes fill this frame (the pipeline's specialization, set where RB_RT_RATES
// is): uniform, so the barrier stays in uniform control flow, and the plain pipeline's
// compiler drops the fill, its barrier and its shared memory.
layout(constant_id = RB_FILL_CONSTANT_ID) const bool rbFill = false;
bool fillsInPass() { return rbFill; }

uint fillIndex(ivec2 pixel) {
  ivec2 a = pixel & (RB_TILE_SIZE - 1);
  return uint(a.y * RB_TILE_SIZE + a.x);
}

// The slots a pixel shares into: its own, and where 1/16 traces it this frame its block's copy
// (else its own again).
uvec2 fillSlots(ivec2 pixel) {
  uint i = fillIndex(pixel);
  uvec2 a = uvec2(pixel & (RB_TILE_SIZE - 1));
  bool sixteenth = all(equal(a & 3u, sixteenthOffset(frame.sizeLightsFrame.w)));
  return uvec2(i, sixteenth ? RB_TILE_PIXELS + (a.x >> 2u) + 2u * (a.y >> 2u) : i);
}

// Each invocation clears its own pixel's slots before its pass writes anything (the copy's
// too: no other invocation writes it).
void clearFillSlot(ivec2 pixel) {
  uvec2 slots = fillSlots(pixel);
  fillObject[slots.x] = RB_NO_OBJECT;
  fillObject[slots.y] = RB_NO_OBJECT;
}

void shareFillSource(uvec2 slots, uint objectId, vec3 position, vec3 normal) {
  for (int n = 0; n < 2; ++n) {
    fillObject[slots[n]] = objectId;
    fillPosition[slots[n]] = position;
    fillNormal[slots[n]] = normal;
  }
}

// The k-th of the 3x3 neighbours a pixel's fill reads at 1/2 and 1/4.
ivec2 fillOffset(int k) { return ivec2(k % 3 - 1, k / 3 - 1); }

// The slot of the neighbour at `offset` from `pixel` and its weight at 1/2 or 1/4; 0 where the
// item's `rate` did not trace it this frame (1 to 4 of 1/4's 9 are left: tested first, the
// cheap way, as shared memory is slow to gather from on lavapipe), outside the tile, on another
// object or where nothing was shared.
float fillWeight(FillCentre c, uint rate, ivec2 pixel, ivec2 offset, out uint slot) {
  ivec2 a = (pixel & (RB_TILE_SIZE - 1)) + offset;
  slot = 0u;
  if (!rateTraces(rate, pixel + offset)) return 0.0;
  if (any(lessThan(a, ivec2(0))) || any(greaterThanEqual(a, ivec2(RB_TILE_SIZE)))) return 0.0;
  slot = uint(a.y * RB_TILE_SIZE + a.x);
  if (fillObject[slot] != c.objectId) return 0.0;
  int d2 = offset.x * offset.x + offset.y * offset.y;
  float near = d2 == 0 ? 1.0 : (d2 == 1 ? 0.60653066 : 0.36787944);  // exp(-d2 / 2)
  return near * fillSimilarity(c, fillPosition[slot], fillNormal[slot]);
}

// 1/16 traces the same four pixels in every tile, so every pixel of the tile fills from the
// same four samples. They are copied to the last four slots, whose constant indices lavapipe
// reads once for all lanes, where an index that differs per lane (or is computed from a
// uniform buffer) it reads lane by lane: those gathers were most of 1/16's fill time. The
// shader reads them once, in its uniform control flow after the barrier.
struct SixteenthSample {
  ivec2 at;  // in the tile
  uint objectId;
  vec3 position;
  vec3 normal;
};

SixteenthSample sixteenthSample(int k) {
  uint slot = RB_TILE_PIXELS + uint(k);
  ivec2 at = ivec2(sixteenthOffset(frame.sizeLightsFrame.w) + uvec2(k & 1, k >> 1) * 4u);
  return SixteenthSample(at, fillObject[slot], fillPosition[slot], fillNormal[slot]);
}

// The weight of a 1/16 sample for the fill of `pixel` (0 on another object or none).
float sixteenthWeight(FillCentre c, SixteenthSample t, ivec2 pixel) {
  if (t.objectId != c.objectId) return 0.0;
  ivec2 d = t.at - (pixel & (RB_TILE_SIZE - 1));
  return exp(-0.125 * float(d.x * d.x + d.y * d.y)) * fillSimilarity(c, t.position, t.normal);
}

#endif
