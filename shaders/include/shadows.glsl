// Shadow-map lookups with percentage-closer filtering: four bilinear depth-compare taps
// half a texel around the point, a smooth 3x3-texel kernel for four fetches. Acne is
// avoided by a normal offset of about 1.5 shadow texels (its world size is known per
// light) plus the slope-scaled depth bias of the shadow pass.
// A map sized from its screen coverage uses the share spotShadow.w of its layer's side
// (ShadowMapPass::fit): coordinates are scaled into that corner and taps clamped inside it.
#ifndef RB_SHADOWS_GLSL
#define RB_SHADOWS_GLSL

const vec2 kPcfOffsets[4] = vec2[4](vec2(-0.5, -0.5), vec2(0.5, -0.5), vec2(-0.5, 0.5), vec2(0.5, 0.5));

// A tap's coordinates kept `margin` texels inside the used corner [0, share]^2 of a layer.
vec2 insideUsed(vec2 uv, float share, vec2 texel, float margin) { return clamp(uv, texel * margin, vec2(share) - texel * margin); }

// Cube-map face addressing (the Vulkan specification's table): the face a direction
// leaves through (+X -X +Y -Y +Z -Z: 0..5) and where on it, in [0, 1]^2. The shadow pass
// renders each face with the matching view (scene_gpu.cpp).
vec2 cubeFaceUv(vec3 d, out float face) {
  vec3 a = abs(d);
  float ma, sc, tc;
  if (a.x >= a.y && a.x >= a.z) {
    face = d.x > 0.0 ? 0.0 : 1.0;
    ma = a.x;
    sc = d.x > 0.0 ? -d.z : d.z;
    tc = -d.y;
  } else if (a.y >= a.z) {
    face = d.y > 0.0 ? 2.0 : 3.0;
    ma = a.y;
    sc = d.x;
    tc = d.y > 0.0 ? d.z : -d.z;
  } else {
    face = d.z > 0.0 ? 4.0 : 5.0;
    ma = a.z;
    sc = d.z > 0.0 ? d.x : -d.x;
    tc = -d.y;
  }
  return 0.5 * vec2(sc, tc) / ma + 0.5;
}

// Four bilinear depth-compare taps half a texel (times `spread`) around `uv` (in [0, 1]^2 of
// the map) in `layer`'s used corner, against `ref`.
float pcf(sampler2DArrayShadow maps, vec2 uv, float layer, float share, float ref, float spread) {
  vec2 texel = 1.0 / vec2(textureSize(maps, 0).xy);
  float sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += texture(maps, vec4(insideUsed(uv * share + kPcfOffsets[i] * texel * spread, share, texel, 0.5), layer, ref));
  return sum * 0.25;
}

// Directional and spot lights: one layer of the 2D array each. `spread` scales the taps'
// distance from the point (1: the PCF kernel, half a texel).
float shadowFromMap(GpuLight light, vec3 position, vec3 normal, float spread) {
  float layer = light.spotShadow.z;
  if (layer < 0.0) return 1.0;
  bool spot = uint(light.directionType.w) == RB_LIGHT_SPOT;
  float texelWorld = light.shadowParams.x * (spot ? max(length(position - light.positionRange.xyz), 1e-3) : 1.0);
  vec4 p = light.shadowViewProj * vec4(position + normal * texelWorld * light.shadowParams.w, 1.0);
  if (p.w <= 0.0) return 1.0;
  p.xyz /= p.w;
  vec2 uv = p.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || p.z > 1.0) return 1.0;
  return pcf(shadowMaps, uv, layer, light.spotShadow.w, p.z, spread);
}
float shadowFromMap(GpuLight light, vec3 position, vec3 normal) { return shadowFromMap(light, position, normal, 1.0); }

// Point lights: six layers (a cube's faces) each. The reference depth is what the face's
// 90-degree perspective projection wrote for this point: it depends only on the largest axis
// of the light-to-point vector, which also picks the face. Taps stay on that face (within
// half a texel of its edge), where a hardware cube lookup would filter across the seam.
float shadowFromCube(GpuLight light, vec3 position, vec3 normal, float spread) {
  float cube = light.spotShadow.z;
  if (cube < 0.0) return 1.0;
  float distanceToLight = length(position - light.positionRange.xyz);
  vec3 v = position + normal * light.shadowParams.x * distanceToLight * light.shadowParams.w - light.positionRange.xyz;
  float n = light.shadowParams.y, f = light.shadowParams.z;
  float d = max(abs(v.x), max(abs(v.y), abs(v.z)));
  if (d >= f || d <= n) return 1.0;
  float ref = f / (f - n) - f * n / ((f - n) * d);
  float face;
  vec2 uv = cubeFaceUv(v, face);
  return pcf(pointShadows, uv, cube * 6.0 + face, light.spotShadow.w, ref, spread);
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

// Where a shadow ray from `origin` towards `light` may end (`dist`: the light, or 1e30 for a
// directional one) with the shadow map's word: a ray towards a light passes through the
// light's centre of projection, so it projects onto the origin's texel all along, and a
// blocker on it lies in the map at that texel, no nearer the light than the nearest depth the
// map holds there. The nearest depth is taken over 6x6 texels around the point (nine gathers):
// texel centres at least two texels away on each side cover the slope-scaled depth bias
// (1.75 texels' slope) of a blocker whose surface spans them; the ray then ends
// RB_SHADOW_RAY_END_TEXELS texels (world size at the receiver) past that depth. Nothing
// rendered there, or the point outside the map: the full ray. A blocker thinner than a texel
// that the map misses entirely is missed here too, as the classifier misses it already
// (docs/SELECTION.md measures what this changes).
#define RB_SHADOW_RAY_END_TEXELS 3.0

// `uv` in the layer's used corner (already scaled by `share`); gathers stay inside it.
float nearestDepthInLayer(sampler2DArray depths, vec2 uv, float layer, float share) {
  vec2 texel = 1.0 / vec2(textureSize(depths, 0).xy);
  float d = 1.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      vec4 g = textureGather(depths, vec3(insideUsed(uv + vec2(x, y) * 2.0 * texel, share, texel, 1.0), layer));
      d = min(d, min(min(g.x, g.y), min(g.z, g.w)));
    }
  return d;
}

// View depth of a perspective (zero-to-one) shadow map's depth value.
float viewDepth(float depth, float n, float f) { return f * n / (f - depth * (f - n)); }

float shadowRayEnd(GpuLight light, vec3 origin, vec3 L, float dist) {
  float layer = light.spotShadow.z;
  if (layer < 0.0) return dist;
  uint type = uint(light.directionType.w);
  float n = light.shadowParams.y, f = light.shadowParams.z;
  float t;      // where the nearest blocker depth is, along the ray
  float texel;  // a texel's world size at the receiver
  if (type == RB_LIGHT_POINT) {
    vec3 v = origin - light.positionRange.xyz;
    vec3 a = abs(v);
    float w0 = max(a.x, max(a.y, a.z));
    if (w0 >= f || w0 <= n) return dist;
    float face;
    vec2 uv = cubeFaceUv(v, face);
    float d = nearestDepthInLayer(pointShadowDepths, uv * light.spotShadow.w, layer * 6.0 + face, light.spotShadow.w);
    if (d >= 1.0) return dist;
    // The major axis's component shrinks linearly along the ray.
    float along = a.x >= max(a.y, a.z) ? abs(L.x) : (a.y >= a.z ? abs(L.y) : abs(L.z));
    t = (w0 - viewDepth(d, n, f)) / max(along, 1e-6);
    texel = light.shadowParams.x * w0;
  } else {
    vec4 c0 = light.shadowViewProj * vec4(origin, 1.0), c1 = light.shadowViewProj * vec4(origin + L, 1.0);
    if (c0.w <= 0.0) return dist;
    vec3 p = c0.xyz / c0.w;
    vec2 uv = p.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || p.z > 1.0) return dist;
    float d = nearestDepthInLayer(shadowMapDepths, uv * light.spotShadow.w, layer, light.spotShadow.w);
    if (d >= 1.0) return dist;
    if (type == RB_LIGHT_SPOT) {
      // View depth falls linearly along the ray (c.w is the spot's view depth).
      t = (c0.w - viewDepth(d, n, f)) / max(c0.w - c1.w, 1e-6);
      texel = light.shadowParams.x * c0.w;
    } else {
      // Orthographic: depth falls linearly along the ray.
      t = (p.z - d) / max(p.z - c1.z, 1e-12);
      texel = light.shadowParams.x;
    }
  }
  return min(dist, max(t, 0.0) + RB_SHADOW_RAY_END_TEXELS * texel);
}

#endif
