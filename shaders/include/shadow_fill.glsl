// The fill of the shadows a reduced ray rate skipped (include/rates.glsl), in the lighting
// pass: at a pixel its shadow item's rate skipped this frame, each light's shadow-map
// visibility is corrected by the weighted mean (include/fill_weights.glsl) of the map's error
// at the pixels around it that the rate traced on the same object: the traced visibility minus
// the map's there, both in the shadow mask (rt_shadows.comp). Filling the correction, not the
// visibility, keeps the map's shadow edges at the map's resolution where the rays agree with
// it, where a filled visibility makes every edge a staircase of the rate's blocks. The traced
// neighbours: at 1/2 the four beside it; at 1/4 those among the 3x3 pixels around it (one to
// four); at 1/16 the four nearest, one per 4x4 block around it. It reads across tiles, as the
// lighting pass runs over every pixel anyway; the trace pass then spends nothing on a skipped
// pixel but reading its object. Where no neighbour qualifies the map stays.
// The includer includes bindings.glsl, gbuffer.glsl and rates.glsl.
#ifndef RB_SHADOW_FILL_GLSL
#define RB_SHADOW_FILL_GLSL
#include "include/fill_weights.glsl"

struct ShadowFill {
  ivec2 at[4];
  float weight[4];
  float total;
};

// The weight of the traced pixel `q` for the fill of c (0 off screen, on another object or unlit).
float shadowSourceWeight(FillCentre c, ivec2 q, float near) {
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), frame.sizeLightsFrame.xy))) return 0.0;
  if (texelFetch(gObjectId, q, 0).r != c.objectId || texelFetch(gRoughTransIor, q, 0).a > 0.5) return 0.0;
  return near * fillSimilarity(c, surfacePosition(q), surfaceNormal(q));
}

// 1/2's traced pixels beside a pixel it skipped.
const ivec2 kHalfRateNeighbours[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));

// The pixels around `pixel` that `rate` traced this frame, and their weights for the fill of c.
ShadowFill shadowFillSources(ivec2 pixel, FillCentre c, uint rate) {
  ShadowFill f;
  f.total = 0.0;
  uint frameIndex = frame.sizeLightsFrame.w;
  bool sixteenth = rate == RB_RATE_SIXTEENTH;
  // 1/4 and 1/16 trace a lattice of spacing 2 or 4: the four lattice points around the pixel.
  ivec2 offset = ivec2(sixteenth ? sixteenthOffset(frameIndex) : quarterOffset(frameIndex));
  int spacing = sixteenth ? 4 : 2;
  ivec2 below = pixel - ((pixel - offset) & (spacing - 1));
  for (int k = 0; k < 4; ++k) {
    ivec2 q = rate == RB_RATE_HALF ? pixel + kHalfRateNeighbours[k] : below + ivec2(k & 1, k >> 1) * spacing;
    ivec2 d = q - pixel;
    float d2 = float(d.x * d.x + d.y * d.y);
    bool near = sixteenth || all(lessThanEqual(abs(d), ivec2(1)));  // 1/4: within the 3x3 pixels around it
    f.at[k] = q;
    f.weight[k] = near ? shadowSourceWeight(c, q, exp(d2 * (sixteenth ? -0.125 : -0.5))) : 0.0;
    f.total += f.weight[k];
  }
  return f;
}

// The fill's correction of light `light`'s shadow-map visibility `mapped` at the pixel: each
// traced neighbour's correction weighted again by how alike the map's visibility is there
// (1 - |difference|)^8, a joint bilateral filter guided by the map: a
// neighbour across one of the map's edges carries the other side's error and counts little
// (0 where nothing qualified).
float shadowFillCorrection(ShadowFill f, uint light, float mapped) {
  float sum = 0.0, total = 0.0;
  for (int k = 0; k < 4; ++k)
    if (f.weight[k] > 0.0) {
      float neighbourMapped = imageLoad(shadowMask, ivec3(f.at[k], mappedLayer(light))).r;
      float guide = max(1.0 - abs(neighbourMapped - mapped), 0.0);
      guide *= guide;  // ^8 by squaring, as fillSimilarity's normal weight: three multiplies where pow is a log and an exp
      guide *= guide;
      guide *= guide;
      float w = f.weight[k] * guide;
      sum += w * (imageLoad(shadowMask, ivec3(f.at[k], int(light))).r - neighbourMapped);
      total += w;
    }
  return total < RB_FILL_MIN_WEIGHT ? 0.0 : sum / total;
}

#endif
