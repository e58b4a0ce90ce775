#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"

// Compose direct + indirect into linear HDR (for EXR), then tonemap with the ACES filmic
// fit of Narkowicz (2015) and encode sRGB for the PNG.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

vec3 acesNarkowicz(vec3 x) {
  const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
  return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

vec3 linearToSrgb(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  vec3 hdr = imageLoad(directImage, pixel).rgb + imageLoad(indirectImage, pixel).rgb;
  hdr = max(hdr, vec3(0.0));
  imageStore(hdrImage, pixel, vec4(hdr, 1.0));
  imageStore(ldrImage, pixel, vec4(linearToSrgb(acesNarkowicz(hdr * frame.exposure.x)), 1.0));
}
