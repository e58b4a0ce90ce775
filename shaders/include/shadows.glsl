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
float cubeFace(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x > 0.0 ? 0.0 : 1.0;
  return a.y >= a.z ? (d.y > 0.0 ? 2.0 : 3.0) : (d.z > 0.0 ? 4.0 : 5.0);
}

// Where `d` meets the plane of `face` (on it or beyond its edges), in its [0, 1]^2, and the
// distance along the face's axis (`major`; not positive: behind the face).
vec2 cubeUvOnFace(vec3 d, float face, out float major) {
  float sc, tc;
  if (face < 2.0) {
    major = face == 0.0 ? d.x : -d.x;
    sc = face == 0.0 ? -d.z : d.z;
    tc = -d.y;
  } else if (face < 4.0) {
    major = face == 2.0 ? d.y : -d.y;
    sc = d.x;
    tc = face == 2.0 ? d.z : -d.z;
  } else {
    major = face == 4.0 ? d.z : -d.z;
    sc = face == 4.0 ? d.x : -d.x;
    tc = -d.y;
  }
  return 0.5 * vec2(sc, tc) / major + 0.5;
}

// Four bilinear depth-compare taps half a texel (times `spread`) around `uv` (in [0, 1]^2 of
// the map) in `layer`'s used corner, each against `ref` plus `slope` (the reference's change
// per unit of the used corner's coordinates; zero: one reference for all four).
float pcf(sampler2DArrayShadow maps, vec2 uv, float layer, float share, float ref, vec2 slope, float spread) {
  vec2 texel = 1.0 / vec2(textureSize(maps, 0).xy);
  float sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    vec2 offset = kPcfOffsets[i] * texel * spread;
    sum += texture(maps, vec4(insideUsed(uv * share + offset, share, texel, 0.5), layer, ref + dot(slope, offset)));
  }
  return sum * 0.25;
}

// A texel's world size where `position` is (the map's used size; a directional light's the
// same everywhere), and the point a lookup of the map takes for a surface point: moved along
// the normal by the normal offset (shadowParams.w texels).
float texelWorldAt(GpuLight light, vec3 position) {
  bool directional = uint(light.directionType.w) == RB_LIGHT_DIRECTIONAL;
  return light.shadowParams.x * (directional ? 1.0 : max(length(position - light.positionRange.xyz), 1e-3));
}
vec3 lookupPoint(GpuLight light, vec3 position, vec3 normal) { return position + normal * texelWorldAt(light, position) * light.shadowParams.w; }

// Where the lookup point `q` lies in `light`'s map: the layer, [0, 1]^2 of the map and the depth
// it is compared against. A point light's cube face is `face` where it is not negative, else
// the one q's direction leaves through (set). False where the map does not hold q (outside
// the map, before its near plane or past its far one): the map's word there is "lit".
// Directional and spot lights: one layer of the 2D array each. Point lights: six layers (a
// cube's faces) each; the reference depth is what the face's 90-degree perspective projection
// wrote for this point, which depends only on the distance along the face's axis.
bool mapCoords(GpuLight light, vec3 q, inout float face, out float layer, out vec2 uv, out float ref) {
  layer = light.spotShadow.z;
  if (uint(light.directionType.w) == RB_LIGHT_POINT) {
    vec3 v = q - light.positionRange.xyz;
    if (face < 0.0) face = cubeFace(v);
    float n = light.shadowParams.y, f = light.shadowParams.z, major;
    uv = cubeUvOnFace(v, face, major);
    ref = f / (f - n) - f * n / ((f - n) * major);
    layer = layer * 6.0 + face;
    return major > n && major < f;
  }
  vec4 p = light.shadowViewProj * vec4(q, 1.0);
  uv = vec2(-1.0);
  ref = 1.0;
  if (p.w <= 0.0) return false;
  p.xyz /= p.w;
  uv = p.xy * 0.5 + 0.5;
  ref = p.z;
  return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) && p.z <= 1.0;
}

// The map's visibility around the lookup point's coordinates (PCF), against `ref` plus `slope`.
float mapVisibility(GpuLight light, float layer, vec2 uv, float ref, vec2 slope, float spread) {
  return uint(light.directionType.w) == RB_LIGHT_POINT ? pcf(pointShadows, uv, layer, light.spotShadow.w, ref, slope, spread)
                                                       : pcf(shadowMaps, uv, layer, light.spotShadow.w, ref, slope, spread);
}

// The fallback's visibility of `light` at the point (the lighting pass's lookup). Taps stay on
// a point light's face (within half a texel of its edge), where a hardware cube lookup would
// filter across the seam.
float shadowFromLight(GpuLight light, vec3 position, vec3 normal) {
  if (light.spotShadow.z < 0.0) return 1.0;
  float face = -1.0, layer, ref;
  vec2 uv;
  if (!mapCoords(light, lookupPoint(light, position, normal), face, layer, uv, ref)) return 1.0;
  return mapVisibility(light, layer, uv, ref, vec2(0.0), 1.0);
}

// A frame of the plane with normal n (Duff et al. 2017, "Building an orthonormal basis,
// revisited").
void planeAxes(vec3 n, out vec3 t1, out vec3 t2) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z), b = n.x * n.y * a;
  t1 = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
  t2 = vec3(b, s + n.y * n.y * a, -n.y);
}

// A triangle whose plane the light meets this close to edge-on, or from behind (the cosine of
// the light's angle to its geometric normal), is left uncertain: the shadow terminator, where a
// smooth shading normal faces a light its triangle does not, and where a plane's depth changes
// by 16 texels' worth or more per texel of the map.
#define RB_SHADOW_EDGE_ON 0.0625

// Whether four depth tests `reach` texels away diagonally agree with the map's certain
// `visibility` (0 or 1) at the surface point `position` with geometric normal `ng` and `L`
// towards the light (rt_common.glsl's lightSample): each
// against the depth of the point's triangle plane where it looks (the receiver plane depth
// bias of Isidoro's "Shadow mapping: GPU-based tips and techniques", GDC 2006, from two texel
// steps along the plane instead of screen derivatives). Against the point's own depth, as the
// lighting pass's taps are, the taps two texels out sank below a curved surface or a plane the
// light sees at a slant by more than the shadow pass's slope bias covers, and called much of
// it uncertain: 3.2x the shadow rays over the benchmark's views, with twice the FLIP against
// full RT (docs/SELECTION.md).
bool wideTapsAgree(GpuLight light, vec3 position, vec3 ng, vec3 L, float reach, float visibility) {
  if (dot(ng, L) < RB_SHADOW_EDGE_ON) return false;
  float face = -1.0, layer, ref0;
  vec2 uv0;
  if (!mapCoords(light, position, face, layer, uv0, ref0)) return true;  // the map's "lit", as the lighting pass takes it
  vec3 t1, t2;
  planeAxes(ng, t1, t2);
  float step = texelWorldAt(light, position), ref1, ref2, l;
  vec2 uv1, uv2;
  mapCoords(light, position + t1 * step, face, l, uv1, ref1);
  mapCoords(light, position + t2 * step, face, l, uv2, ref2);
  // Texel steps along the plane in the used corner's coordinates (a face-on plane's: a texel
  // each), and the plane's depth per unit of them: steps^T slope = the steps' depths.
  mat2 steps = mat2((uv1 - uv0) * light.spotShadow.w, (uv2 - uv0) * light.spotShadow.w);
  if (determinant(steps) == 0.0) return false;
  vec2 slope = vec2(ref1 - ref0, ref2 - ref0) * inverse(steps);
  return mapVisibility(light, layer, uv0, ref0, slope, 2.0 * reach) == visibility;
}

// The shadow classifier: whether the shadow map decides the point for certain, with its
// visibility. Uncertain: the PCF result strictly between lit and shadowed (a shadow edge
// within about a texel), or four depth tests `reach` texels away (diagonally) disagree with
// it (an edge within the reach: where a map's resolution, bias or missing contact shadows
// err), or the point's triangle meets the light edge-on or from behind, or the light has no
// map. reach 0 checks the PCF result alone. `normal` is the shading normal the lighting pass
// looks the map up with, `ng` the triangle's, `L` the direction towards the light.
bool shadowMapCertain(GpuLight light, vec3 position, vec3 normal, vec3 ng, vec3 L, float reach, out float visibility) {
  visibility = shadowFromLight(light, position, normal);
  if (light.spotShadow.z < 0.0 || (visibility > 0.0 && visibility < 1.0)) return false;
  return reach <= 0.0 || wideTapsAgree(light, position, ng, L, reach, visibility);
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
    // The face the origin lies on and where (outside the cube's near and far planes: the full ray).
    float face = -1.0, faceLayer, ref;
    vec2 uv;
    if (!mapCoords(light, origin, face, faceLayer, uv, ref)) return dist;
    vec3 a = abs(origin - light.positionRange.xyz);
    float w0 = max(a.x, max(a.y, a.z));
    float d = nearestDepthInLayer(pointShadowDepths, uv * light.spotShadow.w, faceLayer, light.spotShadow.w);
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
