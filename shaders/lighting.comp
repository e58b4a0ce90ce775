#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/brdf.glsl"
#include "include/gbuffer.glsl"
#include "include/shadows.glsl"

// Deferred direct lighting: every punctual light (GGX/Smith) with its visibility (the
// ray-traced shadow mask where traced, else the shadow maps), emissive, and diffuse ambient
// from the environment. Background pixels get
// the sky. Writes directImage.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

// glTF KHR_lights_punctual range falloff: smooth window to zero at `range`.
float rangeAttenuation(float d, float range) {
  float invSquare = 1.0 / max(d * d, 1e-8);
  if (range <= 0.0) return invSquare;
  float r = d / range;
  float window = clamp(1.0 - r * r * r * r, 0.0, 1.0);
  return window * window * invSquare;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  Surface s;
  if (!readSurface(pixel, s)) {
    imageStore(directImage, pixel, vec4(textureLod(envMap, viewDirection(pixel), 0.0).rgb, 1.0));
    return;
  }
  if (s.unlit) {
    imageStore(directImage, pixel, vec4(s.baseColor, 1.0));
    return;
  }
  vec3 V = normalize(frame.cameraPositionNear.xyz - s.position);
  vec3 N = s.normal;
  vec3 color = s.emissive;
  // Ray-traced visibility replaces the shadow maps where the shadow pass traced: pixels of
  // selected objects.
  bool rtShadows = (frame.rayTracing.x & RB_RT_SHADOWS) != 0u && pixelSelected(s.objectId);
  for (uint i = 0u; i < frame.sizeLightsFrame.z; ++i) {
    GpuLight light = lights[i];
    uint type = uint(light.directionType.w);
    vec3 L;
    float attenuation = 1.0;
    float visibility;
    if (type == RB_LIGHT_DIRECTIONAL) {
      L = -light.directionType.xyz;
      if (dot(N, L) <= 0.0) continue;
      visibility = rtShadows ? imageLoad(shadowMask, ivec3(pixel, int(i))).r : shadowFromMap(light, s.position, N);
    } else {
      vec3 toLight = light.positionRange.xyz - s.position;
      float d = length(toLight);
      L = toLight / max(d, 1e-8);
      if (dot(N, L) <= 0.0) continue;
      attenuation = rangeAttenuation(d, light.positionRange.w);
      if (type == RB_LIGHT_SPOT) {
        float cd = dot(-L, light.directionType.xyz);
        float t = clamp((cd - light.spotShadow.y) / max(light.spotShadow.x - light.spotShadow.y, 1e-4), 0.0, 1.0);
        attenuation *= t * t;
        if (attenuation <= 0.0) continue;
        visibility = rtShadows ? imageLoad(shadowMask, ivec3(pixel, int(i))).r : shadowFromMap(light, s.position, N);
      } else {
        visibility = rtShadows ? imageLoad(shadowMask, ivec3(pixel, int(i))).r : shadowFromCube(light, s.position, N);
      }
    }
    color += shadePbr(N, V, L, s.baseColor, s.metallic, s.roughness, s.transmission, s.ior) * light.colorIntensity.rgb * attenuation *
             visibility;
  }
  // Diffuse ambient: the roughest prefiltered level approximates irradiance / pi.
  vec3 ambient = textureLod(envMap, N, float(RB_ENV_MIPS - 1)).rgb;
  color += ambient * s.baseColor * (1.0 - s.metallic) * (1.0 - s.transmission);
  imageStore(directImage, pixel, vec4(color, 1.0));
}
