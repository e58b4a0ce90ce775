#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
layout(push_constant) uniform PushBlock { DrawPush push; };
#include "include/brdf.glsl"
#include "include/gbuffer.glsl"
#include "include/env_fallback.glsl"
#include "include/screen_pixel.glsl"

// Raster fallback for reflections and refractions (include/env_fallback.glsl). Writes
// reflectionImage and refractionImage; the ray-traced passes replace them for the paths they
// trace.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

void main() {
  ivec2 pixel = screenPixel();
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  Surface s;
  if (!readSurface(pixel, s) || s.unlit) {
    imageStore(reflectionImage, pixel, vec4(0.0));
    imageStore(refractionImage, pixel, vec4(0.0));
    return;
  }
  vec3 V = normalize(frame.cameraPositionNear.xyz - s.position);
  // Behind glass the screen-space reflections and the geometric normal are not this surface's.
  bool behind = behindGlassPass();
  vec3 reflection = envReflection(s, V, behind ? ivec2(-1) : pixel, behind ? s.normal : surfaceGeometricNormal(pixel));
  imageStore(reflectionImage, pixel, vec4(reflection, 1.0));
  imageStore(refractionImage, pixel, vec4(envTransmission(s, V), 1.0));
}
