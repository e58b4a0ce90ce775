#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/brdf.glsl"
#include "include/gbuffer.glsl"

// Raster fallback for reflections and refractions: the prefiltered environment map sampled
// in the reflected and refracted directions (split-sum specular; Snell refraction through
// the surface with KHR_materials_volume attenuation over the thickness). Writes
// indirectImage; the ray-traced passes replace it for selected objects.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

vec3 prefiltered(vec3 dir, float roughness) { return textureLod(envMap, dir, roughness * float(RB_ENV_MIPS - 1)).rgb; }

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  Surface s;
  if (!readSurface(pixel, s) || s.unlit) {
    imageStore(indirectImage, pixel, vec4(0.0));
    return;
  }
  vec3 V = normalize(frame.cameraPositionNear.xyz - s.position);
  vec3 N = s.normal;
  float NoV = clamp(dot(N, V), 1e-4, 1.0);
  vec3 f0 = mix(vec3(f0FromIor(s.ior)), s.baseColor, s.metallic);
  vec3 specularWeight = envBrdfApprox(f0, s.roughness, NoV);
  vec3 color = prefiltered(reflect(-V, N), s.roughness) * specularWeight;

  float transmission = s.transmission * (1.0 - s.metallic);
  if (transmission > 0.0) {
    GpuMaterial m = materials[s.materialId];
    vec3 T = refract(-V, N, 1.0 / max(s.ior, 1.0));
    float thickness = m.normalScaleThicknessFlags.y;
    // Thick volumes bend the ray back on exit through a parallel surface: the exit direction
    // equals -V, offset; thin walls keep the refracted direction (glTF thin-walled model).
    vec3 dir = thickness > 0.0 ? -V : (dot(T, T) > 0.0 ? T : reflect(-V, N));
    if (thickness > 0.0 && dot(T, T) > 0.0) dir = normalize(mix(-V, T, 0.5));
    vec3 transmitted = prefiltered(dir, s.roughness) * s.baseColor;
    float distanceInside = thickness / max(dot(-T, -N), 0.05);
    if (m.attenuationColorDistance.w > 0.0 && thickness > 0.0)
      transmitted *= pow(m.attenuationColorDistance.rgb, vec3(distanceInside / m.attenuationColorDistance.w));
    color += transmitted * transmission * (vec3(1.0) - specularWeight);
  }
  imageStore(indirectImage, pixel, vec4(color, 1.0));
}
