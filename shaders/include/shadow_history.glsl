// The temporal fill of shadows a reduced ray rate skipped (RB_RT_TEMPORAL_FILL), in the lighting
// pass: a pixel its shadow item's rate skips this frame corrects each light's shadow-map
// visibility by the map's error (traced minus the map's visibility) where the point was last
// traced, reprojected to the previous frame, before the spatial fill (include/shadow_fill.glsl)
// from traced neighbours. Unlike a reflection, a shadow does not move with the view: a point's
// visibility is the same from any camera, so a moving view keeps the history wherever the
// point traced still shows within RB_SHADOW_HISTORY_REACH of this pixel's centre. The point
// traced is kept, not the texel's, so that carrying a value from frame to frame does not let it
// drift. The map's error is carried, not the visibility, for the spatial fill's reason: the
// point traced lies up to half a pixel away, and the map's own edges stay where they are (on
// the court under a 2-degree-a-frame orbit at 192x112, carrying the visibility left the frame
// further from full rate than the spatial fill alone, 0.34 against 0.31 in 255ths; the error,
// 0.32).
// It is valid where all of these hold:
//   - it was written by the previous frame, on the same object;
//   - the point traced shows within RB_SHADOW_HISTORY_REACH of this pixel's centre;
//   - it is younger than the item's rate period (1/4: traced three frames ago at most), so a
//     light or a blocker that moves leaves its old shadow for no longer than the rate would.
// A traced pixel writes its errors (age 0); a skipped pixel that found a valid one writes them
// on, a frame older. shadowHistory holds two layers per frame parity: 2p the point traced
// (float bits) and the object; 2p + 1 the first RB_SHADOW_HISTORY_LIGHTS lights' errors, snorm
// 8 bits each (a step of 1/127 of visibility), and the frame that wrote it plus 1 (its low 24
// bits; 0, as the image starts, is no frame) above the age. Further lights have the spatial
// fill alone.
// The includer includes bindings.glsl and rates.glsl.
#ifndef RB_SHADOW_HISTORY_GLSL
#define RB_SHADOW_HISTORY_GLSL
#include "include/fill_history.glsl"

#define RB_SHADOW_HISTORY_REACH 0.5  // pixels: how far from this pixel's centre the point traced may show

struct ShadowHistory {
  uvec3 errors;      // the lights' map errors, four to a word (packSnorm4x8)
  uint age;          // frames since traced (RB_HISTORY_NONE: nothing valid)
  vec3 point;        // where they were traced
};

ShadowHistory noShadowHistory() { return ShadowHistory(uvec3(0u), RB_HISTORY_NONE, vec3(0.0)); }

// The map's error for light `light` (< RB_SHADOW_HISTORY_LIGHTS).
float shadowHistoryError(ShadowHistory h, uint light) {
  vec4 four = unpackSnorm4x8(h.errors[light >> 2u]);
  return four[light & 3u];
}

// The frame tag and age word: frame `f` plus 1, its low 24 bits, above the age.
uint shadowHistoryStamp(uint f, uint age) { return ((f + 1u) << 8u) | age; }

// The history at texel `at` of the previous frame's `layer` if it is valid for a point of object
// `objectId` at `pixel` skipped by `rate`: its traced point shows within `reach` of the pixel's
// centre (`reach` then becomes that distance); else age RB_HISTORY_NONE.
ShadowHistory shadowHistoryAt(ivec2 at, uint layer, ivec2 pixel, uint objectId, uint rate, inout float reach) {
  ShadowHistory h = noShadowHistory();
  if (any(lessThan(at, ivec2(0))) || any(greaterThanEqual(at, ivec2(frame.sizeLightsFrame.xy)))) return h;
  uvec4 where = imageLoad(shadowHistory, ivec3(at, layer));
  if (where.w != objectId) return h;
  vec3 point = uintBitsToFloat(where.xyz);
  vec4 clip = frame.viewProj * vec4(point, 1.0);
  if (clip.w <= 0.0) return h;
  float off = distance((clip.xy / clip.w * 0.5 + 0.5) * vec2(frame.sizeLightsFrame.xy), vec2(pixel) + 0.5);
  if (off > reach) return h;
  uvec4 values = imageLoad(shadowHistory, ivec3(at, layer + 1u));
  uint age = values.w & 0xFFu;
  if ((values.w & ~0xFFu) != shadowHistoryStamp(frame.sizeLightsFrame.w - 1u, 0u) || age + 1u >= ratePeriod(rate)) return h;
  reach = off;
  return ShadowHistory(values.xyz, age, point);
}

// What the previous frame left for the point `p` of object `objectId` at `pixel`, which `rate`
// skips this frame, or age RB_HISTORY_NONE: the texel where the previous frame shows p if it is
// valid, else the valid one of the other three around the point whose point traced shows
// nearest this pixel's centre (at a silhouette the nearest texel may hold the object behind;
// searching them only there left a 1-degree orbit's frame further from full rate, 0.90 against
// 0.86 in tests/temporal_fill_test.cpp).
ShadowHistory previousShadowHistory(ivec2 pixel, vec3 p, uint objectId, uint rate) {
  vec2 uv;
  if (frame.previousCamera.w == 0.0 || !previousUv(p, uv)) return noShadowHistory();
  uint layer = ((frame.sizeLightsFrame.w - 1u) & 1u) * 2u;
  vec2 texel = uv * vec2(frame.sizeLightsFrame.xy);
  ivec2 nearest = ivec2(floor(texel));
  float reach = RB_SHADOW_HISTORY_REACH;
  ShadowHistory h = shadowHistoryAt(nearest, layer, pixel, objectId, rate, reach);
  if (h.age != RB_HISTORY_NONE) return h;
  // The other texels of the 2x2 block whose centres surround the point.
  ivec2 away = ivec2(greaterThanEqual(fract(texel), vec2(0.5))) * 2 - 1;
  for (int k = 1; k < 4; ++k) {
    ShadowHistory other = shadowHistoryAt(nearest + ivec2(k & 1, k >> 1) * away, layer, pixel, objectId, rate, reach);
    if (other.age != RB_HISTORY_NONE) h = other;
  }
  return h;
}

// This frame's history at `pixel` on object `objectId`.
void writeShadowHistory(ivec2 pixel, ShadowHistory h, uint objectId) {
  uint layer = (frame.sizeLightsFrame.w & 1u) * 2u;
  imageStore(shadowHistory, ivec3(pixel, layer), uvec4(floatBitsToUint(h.point), objectId));
  imageStore(shadowHistory, ivec3(pixel, layer + 1u), uvec4(h.errors, shadowHistoryStamp(frame.sizeLightsFrame.w, h.age)));
}

#endif
