#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/display.glsl"

// Compose direct + reflected + refracted light into linear HDR (for EXR), then the display transform
// (include/display.glsl) for the PNG.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  storeComposed(pixel, imageLoad(directImage, pixel).rgb, indirectLight(pixel));
}
