// Shadow-map lookups with percentage-closer filtering: four bilinear depth-compare taps
// half a texel around the point, a smooth 3x3-texel kernel for four fetches. Acne is
// avoided by a normal offset of about 1.5 shadow texels (its world size is known per
// light) plus the slope-scaled depth bias of the shadow pass.
#ifndef RB_SHADOWS_GLSL
#define RB_SHADOWS_GLSL

const vec2 kPcfOffsets[4] = vec2[4](vec2(-0.5, -0.5), vec2(0.5, -0.5), vec2(-0.5, 0.5), vec2(0.5, 0.5));

// Directional and spot lights: one layer of the 2D array each.
float shadowFromMap(GpuLight light, vec3 position, vec3 normal) {
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
  for (int i = 0; i < 4; ++i) sum += texture(shadowMaps, vec4(uv + kPcfOffsets[i] * texel, layer, p.z));
  return sum * 0.25;
}

// Point lights: one cube (6 layers) of the cube array each. The reference depth is what the
// face's 90-degree perspective projection wrote for this point: it depends only on the
// largest axis of the light-to-point vector.
float shadowFromCube(GpuLight light, vec3 position, vec3 normal) {
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
  float spread = light.shadowParams.x;  // one texel, in direction units
  float sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += texture(pointShadows, vec4(dir + (t * kPcfOffsets[i].x + b * kPcfOffsets[i].y) * spread, cube), ref);
  return sum * 0.25;
}

#endif
