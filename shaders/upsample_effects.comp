#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/brdf.glsl"
#include "include/gbuffer.glsl"
#include "include/env_fallback.glsl"
#include "include/rates.glsl"
#define RB_UPSAMPLE_TILES
#include "include/tile_pixel.glsl"
#include "include/upsample.glsl"

// Fills the reflection and refraction paths that an item at a reduced ray rate did not trace
// this frame: the bilateral mean (include/upsample.glsl) of the path's radiance at the pixels
// nearby that traced it this frame (rt_effects.comp stored it without the surface's weight,
// with the frame's stamp), times this pixel's own weight, replaces the path's environment
// fallback in indirectImage; where no neighbour qualifies the fallback stays. Runs over the
// tiles holding items at a reduced rate (tile_list.comp), after the effects pass.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

void main() {
  ivec2 pixel = tilePixel();
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  uint effects = frame.rayTracing.x;
  bool maybe[2] = bool[2]((effects & RB_RT_REFLECTIONS) != 0u && pendingObject(pixel, RB_ITEM_REFLECTIONS) != RB_NO_OBJECT,
                          (effects & RB_RT_REFRACTIONS) != 0u && pendingObject(pixel, RB_ITEM_REFRACTIONS) != RB_NO_OBJECT);
  if (!maybe[0] && !maybe[1]) return;
  Surface s;
  readSurface(pixel, s);
  // The paths the effects pass would have traced here (rt_effects.comp's tests).
  bool pending[2] = bool[2](maybe[0] && s.roughness <= uintBitsToFloat(frame.rayTracing.z), maybe[1] && s.transmission * (1.0 - s.metallic) > 0.0);
  if (!pending[0] && !pending[1]) return;
  UpsampleCentre c = upsampleCentre(pixel, s.objectId);
  uint now = frame.sizeLightsFrame.w & 0x3FFFFFFFu;
  vec3 sum[2] = vec3[2](vec3(0.0), vec3(0.0));
  float weights[2] = float[2](0.0, 0.0);
  for (int y = -RB_UPSAMPLE_RADIUS; y <= RB_UPSAMPLE_RADIUS; ++y)
    for (int x = -RB_UPSAMPLE_RADIUS; x <= RB_UPSAMPLE_RADIUS; ++x) {
      ivec2 q = pixel + ivec2(x, y);
      float w = upsampleWeight(c, q, ivec2(x, y));
      if (w <= 0.0) continue;
      uint stamp = imageLoad(tracedStamp, q).r;
      if ((stamp >> 2) != now) continue;  // traced in another frame, or never
      if (pending[0] && (stamp & 1u) != 0u) {
        sum[0] += w * imageLoad(reflectionRadiance, q).rgb;
        weights[0] += w;
      }
      if (pending[1] && (stamp & 2u) != 0u) {
        sum[1] += w * imageLoad(refractionRadiance, q).rgb;
        weights[1] += w;
      }
    }
  vec3 p, ng, N, V, specularWeight, transmitWeight;
  readExactSurface(pixel, p, ng);
  tracedPathWeights(s, p, ng, N, V, specularWeight, transmitWeight);
  vec3 rasterV = normalize(frame.cameraPositionNear.xyz - s.position);
  vec3 indirect = imageLoad(indirectImage, pixel).rgb;
  if (weights[0] >= RB_UPSAMPLE_MIN_WEIGHT) indirect += sum[0] / weights[0] * specularWeight - envReflection(s, rasterV);
  if (weights[1] >= RB_UPSAMPLE_MIN_WEIGHT) indirect += sum[1] / weights[1] * transmitWeight - envTransmission(s, rasterV);
  imageStore(indirectImage, pixel, vec4(indirect, 1.0));
}
