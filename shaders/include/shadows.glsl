// Shadow-map lookups with percentage-closer filtering: four bilinear depth-compare taps
// half a texel around the point, a smooth 3x3-texel kernel for four fetches. Acne is
// avoided by a normal offset of about 1.5 shadow texels (its world size is known per
// light) plus the slope-scaled depth bias of the shadow pass.
#ifndef RB_SHADOWS_GLSL
#define RB_SHADOWS_GLSL

const vec2 kPcfOffsets[4] = vec2[4](vec2(-0.5, -0.5), vec2(0.5, -0.5), vec2(-0.5, 0.5), vec2(0.5, 0.5));

// Directional and spot lights: one layer of the 2D array each. `spread` scales the taps'
// distance from the point (1: the PCF kernel, half a texel).
float shadowFromMap(GpuLight light, vec3 position, vec3 normal, float spread) {
  float layer = light.spotShadow.z;
  if (layer < 0.0) return 1.0;
  bool spot = uint(light.directionType.w) == RB_LIGHT_SPOT;
  float texelWorld = light.shadowParams.x * (spot ? max(length(position - light.positionRange.xyz), 1e-3) : 1.0);
  vec4 p = light.shadowViewProj * vec4(position + normal * texelWorld * 1.5, 1.0);
  if (p.w <= 0.0) return 1.0;
  p.xyz /= p.w;
  vec2 uv = p.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || p.z > 1.0) return 1.0;
  vec2 texel = 1.0 / vec2(textureSize(shadowMaps, 0).xy);
  float sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += texture(shadowMaps, vec4(uv + kPcfOffsets[i] * texel * spread, layer, p.z));
  return sum * 0.25;
}
float shadowFromMap(GpuLight light, vec3 position, vec3 normal) { return shadowFromMap(light, position, normal, 1.0); }

// Point lights: one cube (6 layers) of the cube array each. The reference depth is what the
// face's 90-degree perspective projection wrote for this point: it depends only on the
// largest axis of the light-to-point vector.
float shadowFromCube(GpuLight light, vec3 position, vec3 normal, float spreadScale) {
  float cube = light.spotShadow.z;
  if (cube < 0.0) return 1.0;
  float distanceToLight = length(position - light.positionRange.xyz);
  vec3 v = position + normal * light.shadowParams.x * distanceToLight * 1.5 - light.positionRange.xyz;
  float n = light.shadowParams.y, f = light.shadowParams.z;
  float d = max(abs(v.x), max(abs(v.y), abs(v.z)));
  if (d >= f || d <= n) return 1.0;
  float ref = f / (f - n) - f * n / ((f - n) * d);
  vec3 dir = v / max(length(v), 1e-12);
  vec3 up = abs(dir.y) < 0.99 ? vec3(0, 1, 0) : vec3(1, 0, 0);
  vec3 t = normalize(cross(up, dir)), b = cross(dir, t);
  float spread = light.shadowParams.x * spreadScale;  // one texel, in direction units
  float sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += texture(pointShadows, vec4(dir + (t * kPcfOffsets[i].x + b * kPcfOffsets[i].y) * spread, cube), ref);
  return sum * 0.25;
}
float shadowFromCube(GpuLight light, vec3 position, vec3 normal) { return shadowFromCube(light, position, normal, 1.0); }

// The fallback's visibility of `light` at the point, its taps `spread` times as far out as
// the lighting pass's PCF (spread 1: the lighting pass's lookup).
float shadowFromLight(GpuLight light, vec3 position, vec3 normal, float spread) {
  return uint(light.directionType.w) == RB_LIGHT_POINT ? shadowFromCube(light, position, normal, spread) : shadowFromMap(light, position, normal, spread);
}
float shadowFromLight(GpuLight light, vec3 position, vec3 normal) { return shadowFromLight(light, position, normal, 1.0); }

// The shadow classifier: whether the shadow map decides the point for certain, with its
// visibility. Uncertain: the PCF result strictly between lit and shadowed (a shadow edge
// within about a texel), or four depth tests `reach` texels away (diagonally) disagree with
// it (an edge within the reach: where a map's resolution, bias or missing contact shadows
// err), or the light has no map. reach 0 checks the PCF result alone.
bool shadowMapCertain(GpuLight light, vec3 position, vec3 normal, float reach, out float visibility) {
  visibility = shadowFromLight(light, position, normal);
  if (light.spotShadow.z < 0.0 || (visibility > 0.0 && visibility < 1.0)) return false;
  return reach <= 0.0 || shadowFromLight(light, position, normal, 2.0 * reach) == visibility;
}

#endif
