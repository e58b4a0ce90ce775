// Procedural sky: a horizon-to-zenith gradient, a darker ground and a sun disk with a soft
// glow. Radiance is linear HDR; frame.sunDirection.w scales it.
#ifndef RB_SKY_GLSL
#define RB_SKY_GLSL

vec3 skyRadiance(vec3 dir, vec3 sunDir, float intensity) {
  float up = dir.y;
  vec3 zenith = vec3(0.22, 0.42, 0.85);
  vec3 horizon = vec3(0.75, 0.82, 0.92);
  vec3 ground = vec3(0.32, 0.29, 0.26);
  vec3 sky = up >= 0.0 ? mix(horizon, zenith, pow(clamp(up, 0.0, 1.0), 0.5)) : mix(horizon, ground, clamp(-up * 4.0, 0.0, 1.0));
  float cosSun = dot(dir, sunDir);
  vec3 sun = vec3(1.0, 0.95, 0.85) * (smoothstep(0.9995, 0.9998, cosSun) * 200.0 + pow(max(cosSun, 0.0), 64.0) * 1.5);
  return (sky + (up > -0.02 ? sun : vec3(0.0))) * intensity;
}

// Direction through texel (x, y) of cube face `face` (Vulkan / GL face conventions).
vec3 cubeDirection(uint face, uvec2 xy, uint size) {
  vec2 uv = (vec2(xy) + 0.5) / float(size) * 2.0 - 1.0;
  vec3 d;
  if (face == 0u) d = vec3(1.0, -uv.y, -uv.x);
  else if (face == 1u) d = vec3(-1.0, -uv.y, uv.x);
  else if (face == 2u) d = vec3(uv.x, 1.0, uv.y);
  else if (face == 3u) d = vec3(uv.x, -1.0, -uv.y);
  else if (face == 4u) d = vec3(uv.x, -uv.y, 1.0);
  else d = vec3(-uv.x, -uv.y, -1.0);
  return normalize(d);
}

#endif
