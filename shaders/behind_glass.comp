#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
layout(push_constant) uniform PushBlock { DrawPush push; };
#include "include/gbuffer.glsl"
#include "include/screen_pixel.glsl"

// The opaque frame (direct + reflected + refracted light, lit before the transmissive surfaces are drawn) into
// mip 0 of the behind-glass image, at half the frame's resolution (every second pixel), over
// the rectangle around the glass in view, with each pixel's view distance in alpha (0, in
// front of everything, where the image was cleared): the mips are blitted after, and
// transmissive surfaces sample it (include/env_fallback.glsl).
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

void main() {
  ivec2 pixel = screenPixel();
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  vec3 radiance = max(imageLoad(directImage, pixel).rgb + indirectLight(pixel), vec3(0.0));
  float distance = RB_BEHIND_GLASS_SKY;
  if (texelFetch(gObjectId, pixel, 0).r != RB_NO_OBJECT)
    distance = min(length(surfacePosition(pixel) - frame.cameraPositionNear.xyz), RB_BEHIND_GLASS_SKY);
  imageStore(behindGlassImage, pixel / int(screenStride()), vec4(min(radiance, vec3(65000.0)), distance));
}
