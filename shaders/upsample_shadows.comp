#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/gbuffer.glsl"
#include "include/rates.glsl"
#define RB_UPSAMPLE_TILES
#include "include/tile_pixel.glsl"
#include "include/upsample.glsl"
#include "include/shadows.glsl"

// Fills the shadow mask where a shadow item at a reduced ray rate left a light's ray for later
// (RB_MASK_PENDING, rt_shadows.comp): the bilateral mean of the light's visibility at the
// pixels traced or classified certain this frame nearby (include/upsample.glsl), else the
// shadow map's. Written with RB_MASK_FILLED added, so that no invocation reads a filled value;
// the lighting pass takes it off. Runs over the tiles holding items at a reduced rate
// (tile_list.comp), after the shadow pass. Lights go four at a time, each neighbour's weight
// computed once per four.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

void main() {
  ivec2 pixel = tilePixel();
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  uint objectId = pendingObject(pixel, RB_ITEM_SHADOWS);
  if (objectId == RB_NO_OBJECT) return;
  UpsampleCentre c;
  bool read = false;  // the centre's G-buffer, once a light is pending
  uint lightCount = frame.sizeLightsFrame.z;
  for (uint first = 0u; first < lightCount; first += 4u) {
    bvec4 pending;
    for (uint k = 0u; k < 4u; ++k)
      pending[k] = first + k < lightCount && imageLoad(shadowMask, ivec3(pixel, int(first + k))).r == RB_MASK_PENDING;
    if (!any(pending)) continue;
    if (!read) c = upsampleCentre(pixel, objectId);
    read = true;
    vec4 sum = vec4(0.0), weights = vec4(0.0);
    for (int y = -RB_UPSAMPLE_RADIUS; y <= RB_UPSAMPLE_RADIUS; ++y)
      for (int x = -RB_UPSAMPLE_RADIUS; x <= RB_UPSAMPLE_RADIUS; ++x) {
        ivec2 q = pixel + ivec2(x, y);
        float w = upsampleWeight(c, q, ivec2(x, y));
        if (w <= 0.0) continue;
        for (uint k = 0u; k < 4u; ++k) {
          if (!pending[k]) continue;
          float v = imageLoad(shadowMask, ivec3(q, int(first + k))).r;
          if (v < 0.0 || v > 1.0) continue;  // pending, or filled by this pass
          sum[k] += w * v;
          weights[k] += w;
        }
      }
    for (uint k = 0u; k < 4u; ++k) {
      if (!pending[k]) continue;
      uint i = first + k;
      float visible = weights[k] >= RB_UPSAMPLE_MIN_WEIGHT ? sum[k] / weights[k] : shadowFromLight(lights[i], worldFromDepth(pixel, texelFetch(gDepth, pixel, 0).r), c.normal);
      imageStore(shadowMask, ivec3(pixel, int(i)), vec4(visible + RB_MASK_FILLED));
    }
  }
}
