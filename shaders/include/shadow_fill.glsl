// The fill of the shadows a reduced ray rate skipped (include/rates.glsl), in the lighting
// pass: at a pixel its shadow item's rate skipped this frame, each light's shadow-map
// visibility is corrected by the weighted mean (include/fill_weights.glsl) of the map's error
// at the pixels around it that the rate traced on the same object: the traced visibility minus
// the map's there, both in the shadow mask (rt_shadows.comp). Filling the correction, not the
// visibility, keeps the map's shadow edges at the map's resolution where the rays agree with
// it, where a filled visibility makes every edge a staircase of the rate's blocks. The traced
// neighbours (fillSources) are read across tiles (those the item is traced in), as the lighting pass runs over every pixel
// anyway; the trace pass then spends nothing on a skipped pixel but reading its object. Where
// no neighbour qualifies the map stays.
// The includer includes bindings.glsl, gbuffer.glsl and rates.glsl.
#ifndef RB_SHADOW_FILL_GLSL
#define RB_SHADOW_FILL_GLSL
#include "include/fill_weights.glsl"

// The fill's correction of light `light`'s shadow-map visibility `mapped` at the pixel: each
// traced neighbour's correction weighted again by how alike the map's visibility is there
// (1 - |difference|)^8, a joint bilateral filter guided by the map: a
// neighbour across one of the map's edges carries the other side's error and counts little
// (0 where nothing qualified).
float shadowFillCorrection(FillSources f, uint light, float mapped) {
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
