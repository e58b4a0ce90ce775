// A punctual light as seen from a surface point, for the lighting pass and the ray-traced
// passes alike (KHR_lights_punctual): the direction towards it, its distance (1e30 for a
// directional light) and the scale of its unshadowed radiance there: inverse square, times the
// glTF range's smooth window to zero at `range` (1 - (d / range)^4, squared) where it has one,
// times a spot's cone: the linear ramp from the outer to the inner cone's cosine, squared. False
// where the light adds nothing (past its range, outside its cone): no shading, no shadow lookup
// and no shadow ray there.
// The includer includes bindings.glsl.
#ifndef RB_LIGHTS_GLSL
#define RB_LIGHTS_GLSL

bool lightSample(GpuLight light, vec3 p, out vec3 L, out float dist, out float scale) {
  uint type = uint(light.directionType.w);
  scale = 1.0;
  if (type == RB_LIGHT_DIRECTIONAL) {
    L = -light.directionType.xyz;
    dist = 1e30;
    return true;
  }
  vec3 toLight = light.positionRange.xyz - p;
  dist = length(toLight);
  L = toLight / max(dist, 1e-8);
  float range = light.positionRange.w;
  float inv = 1.0 / max(dist * dist, 1e-8);
  if (range > 0.0) {
    float r = dist / range;
    float window = clamp(1.0 - r * r * r * r, 0.0, 1.0);
    inv *= window * window;
  }
  scale = inv;
  if (type == RB_LIGHT_SPOT) {
    float cd = dot(-L, light.directionType.xyz);
    float t = clamp((cd - light.spotShadow.y) / max(light.spotShadow.x - light.spotShadow.y, 1e-4), 0.0, 1.0);
    scale *= t * t;
  }
  return scale > 0.0;
}

#endif
