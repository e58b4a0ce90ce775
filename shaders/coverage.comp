#version 460
#extension GL_GOOGLE_include_directive : require
// Coverage: per object, the pixels it covers in the object-ID buffer and the sums of their
// coordinates (for A and the centroid behind P), and per 8x8 tile the objects it shows.
// One invocation per tile sums its pixels in registers for up to RB_TILE_OBJECT_WORDS - 1
// objects and does the atomics once per object and tile (a pixel of a further object adds
// its own and marks the tile crowded). Per-subgroup atomics (one per row of a tile and
// object) cost ~1.4 ms at 640x360 on lavapipe, most of it contention on a few objects'
// records. The 64-bit coordinate sums are kept as lo/hi words with an explicit carry.
#include "include/bindings.glsl"

layout(local_size_x = 64) in;

void addWide(uint index, uint word, uint value) {
  // word 1: sum x (lo at .y, hi at .z); word 3: sum y (lo at .w, hi at sumYHi.x).
  uint old = word == 1u ? atomicAdd(coverage[index].pixelsSumX.y, value) : atomicAdd(coverage[index].pixelsSumX.w, value);
  if (old + value < old) {
    if (word == 1u) atomicAdd(coverage[index].pixelsSumX.z, 1u);
    else atomicAdd(coverage[index].sumYHi.x, 1u);
  }
}

void addCoverage(uint id, uint pixels, uint sumX, uint sumY) {
  if (pixels == 0u) return;
  atomicAdd(coverage[id].pixelsSumX.x, pixels);
  addWide(id, 1u, sumX);
  addWide(id, 3u, sumY);
}

// A tile's object slot: its ID, pixel count and coordinate sums (64 pixels of coordinates
// below 2^16: the sums fit 32 bits).
#define RB_ADD_TO_SLOT(slot) { slot.y += 1u; slot.z += x; slot.w += y; }

void main() {
  uvec2 size = frame.sizeLightsFrame.xy;
  uint tilesX = (size.x + RB_TILE_SIZE - 1u) / RB_TILE_SIZE, tilesY = (size.y + RB_TILE_SIZE - 1u) / RB_TILE_SIZE;
  uint t = gl_GlobalInvocationID.x;
  if (t >= tilesX * tilesY) return;
  uvec2 first = uvec2(t % tilesX, t / tilesX) * RB_TILE_SIZE, last = min(first + RB_TILE_SIZE, size);
  // Three slots (x: object ID, RB_NO_OBJECT while free); explicit variables, not an array
  // indexed at run time, which lavapipe would spill.
  uvec4 s0 = uvec4(RB_NO_OBJECT, 0u, 0u, 0u), s1 = s0, s2 = s0;
  bool crowded = false;
  for (uint y = first.y; y < last.y; ++y)
    for (uint x = first.x; x < last.x; ++x) {
      uint id = texelFetch(gObjectId, ivec2(x, y), 0).r;
      if (id == RB_NO_OBJECT) continue;
      if (s0.x == RB_NO_OBJECT) s0.x = id;
      if (id == s0.x) RB_ADD_TO_SLOT(s0)
      else {
        if (s1.x == RB_NO_OBJECT) s1.x = id;
        if (id == s1.x) RB_ADD_TO_SLOT(s1)
        else {
          if (s2.x == RB_NO_OBJECT) s2.x = id;
          if (id == s2.x) RB_ADD_TO_SLOT(s2)
          else {
            crowded = true;
            addCoverage(id, 1u, x, y);
          }
        }
      }
    }
  addCoverage(s0.x, s0.y, s0.z, s0.w);
  addCoverage(s1.x, s1.y, s1.z, s1.w);
  addCoverage(s2.x, s2.y, s2.z, s2.w);
  // The tile's objects for the tile list (shared/config.h): ID + 1 per slot, 0 when free
  // (RB_NO_OBJECT + 1 wraps to 0); every tile writes all its words, so none needs a clear.
  uint base = t * RB_TILE_OBJECT_WORDS;
  tileObjects[base] = s0.x + 1u;
  tileObjects[base + 1u] = s1.x + 1u;
  tileObjects[base + 2u] = s2.x + 1u;
  tileObjects[base + 3u] = crowded ? 1u : 0u;
}
