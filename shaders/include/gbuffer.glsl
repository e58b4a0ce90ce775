// Reading the G-buffer in the screen-space compute passes.
#ifndef RB_GBUFFER_GLSL
#define RB_GBUFFER_GLSL

#include "include/material_layers.glsl"
#include "include/octahedral.glsl"

struct Surface {
  vec3 position;          // reconstructed from depth (raster passes)
  vec3 normal;
  vec3 baseColor;
  float metallic;
  float roughness;
  float transmission;
  float ior;
  bool unlit;
  bool seenFromInside;    // the back of a one-sided surface: the camera is inside its model
  vec3 emissive;
  uint objectId;
  uint materialId;
  Layers layers;
};

vec3 worldFromDepth(ivec2 pixel, float depth) {
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(frame.sizeLightsFrame.xy) * 2.0 - 1.0;
  vec4 p = frame.invViewProj * vec4(ndc, depth, 1.0);
  return p.xyz / p.w;
}

// Camera ray direction through a pixel (for the background).
vec3 viewDirection(ivec2 pixel) {
  return normalize(worldFromDepth(pixel, 1.0) - frame.cameraPositionNear.xyz);
}

// A pixel's world position and shading normal, as the G-buffer holds them.
vec3 surfacePosition(ivec2 pixel) { return worldFromDepth(pixel, texelFetch(gDepth, pixel, 0).r); }
vec3 surfaceNormal(ivec2 pixel) { return normalize(texelFetch(gNormal, pixel, 0).xyz); }

bool readSurface(ivec2 pixel, out Surface s) {
  s.objectId = texelFetch(gObjectId, pixel, 0).r;
  if (s.objectId == RB_NO_OBJECT) return false;
  s.position = surfacePosition(pixel);
  vec4 normal = texelFetch(gNormal, pixel, 0);
  s.normal = normalize(normal.xyz);
  s.seenFromInside = normal.w > 0.5;
  vec4 bm = texelFetch(gBaseMetal, pixel, 0);
  s.baseColor = bm.rgb;
  s.metallic = bm.a;
  vec4 rti = texelFetch(gRoughTransIor, pixel, 0);
  s.roughness = rti.r;
  s.transmission = rti.g;
  s.ior = rti.b;
  s.unlit = rti.a > 0.5;
  vec4 emissive = texelFetch(gEmissive, pixel, 0);
  s.emissive = emissive.rgb;
  s.materialId = texelFetch(gMaterialId, pixel, 0).r;
  // The layers where the emissive target's alpha says the pixel has some; a host's G-buffer
  // without layers: its materials' factors.
  if (frame.exposure.w < 0.5) s.layers = materialLayers(materials[s.materialId], vec2(0.0), s.normal, s.ior, false);
  else s.layers = emissive.a > 0.5 ? unpackLayers(texelFetch(gLayers, pixel, 0), s.normal, s.ior) : noLayers(s.normal, s.ior);
  return true;
}

// The channels that say which effects the surface shows (roughness, transmission, IOR, unlit,
// and metallic where the surface transmits: it decides only whether it refracts, and 0 stands
// elsewhere): one or two of readSurface's seven fetches. Returns whether the surface is lit.
bool readEffectChannels(ivec2 pixel, inout Surface s) {
  vec4 rti = texelFetch(gRoughTransIor, pixel, 0);
  s.roughness = rti.r;
  s.transmission = rti.g;
  s.ior = rti.b;
  s.unlit = rti.a > 0.5;
  s.metallic = s.transmission > 0.0 ? texelFetch(gBaseMetal, pixel, 0).a : 0.0;
  return !s.unlit;
}

// The part of the surface that the shadow rays and a reduced rate's fill read at a pixel
// (object, position, normal, and the channels that say which effects the surface shows):
// three or four of readSurface's seven fetches, no layers, where those fetches are much of
// what a pixel of theirs costs on lavapipe. The rest of the surface is not read.
bool readSurfacePoint(ivec2 pixel, uint objectId, out Surface s) {
  s.objectId = objectId;
  s.position = surfacePosition(pixel);
  s.normal = surfaceNormal(pixel);
  s.seenFromInside = false;  // not read by them
  bool lit = readEffectChannels(pixel, s);
  s.layers = noLayers(s.normal, s.ior);  // not read by them
  return lit;
}

// The geometric normal (towards the viewer) a texel of the G-buffer's position target holds in w.
vec3 geometricNormalIn(vec4 positionTexel) { return octDecode(unpackSnorm2x16(floatBitsToUint(positionTexel.w))); }

// The exact world position and the geometric normal of a pixel, for secondary rays.
void readExactSurface(ivec2 pixel, out vec3 position, out vec3 geometricNormal) {
  vec4 p = texelFetch(gPosition, pixel, 0);
  position = p.xyz;
  geometricNormal = geometricNormalIn(p);
}

vec3 surfaceGeometricNormal(ivec2 pixel) { return geometricNormalIn(texelFetch(gPosition, pixel, 0)); }

// The shading normal N turned to the viewer's side of the surface (geometric normal ng, towards
// the viewer): where the camera sees a one-sided surface from behind, its normal faces away.
vec3 viewerSideNormal(vec3 N, vec3 ng) { return dot(N, ng) < 0.0 ? -N : N; }

// The mirror direction of the view direction V (towards the viewer) about the shading normal
// N, turned back above the surface (geometric normal ng) where a normal map tilted it below:
// the traced reflection's and its fallbacks' alike.
vec3 mirrorDirection(vec3 V, vec3 N, vec3 ng) {
  vec3 R = reflect(-V, N);
  return dot(R, ng) < 0.0 ? reflect(R, ng) : R;
}

#endif
