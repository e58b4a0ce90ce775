// Shared pieces of the ray-traced effect passes: hit attributes, alpha-tested visibility
// rays, and shading of a surface hit by a secondary ray (direct light with its own shadow
// rays, emissive, environment ambient).
#ifndef RB_RT_COMMON_GLSL
#define RB_RT_COMMON_GLSL
#include "include/bindings.glsl"
#include "include/brdf.glsl"
#include "include/lights.glsl"
#include "include/material_layers.glsl"
#include "include/normal_map.glsl"
#include "include/rayquery.glsl"
#include "include/tile_pixel.glsl"
#include "shared/offset_ray.h"

// Rays this invocation traced (every ray query counts one), and those an item's prior prices
// for the paths it traced (shared/selection.h's RB_ITEM_PRIOR_RAYS), which the cost model's
// time of a ray is measured in for items (cost_model.h's TimeScale::priorWorkPerRay).
uint rbRays = 0u, rbPriorRays = 0u;

// The prior's rays of an item of `effect` (RB_ITEM_*) at one traced pixel.
uint priorRays(uint effect) { return RB_ITEM_PRIOR_RAYS(frame.sizeLightsFrame.z, effect); }

// Adds this invocation's traversal work to its object's counter: lanes of the subgroup
// that traced the same object are summed first, one atomic per object and subgroup; and its
// rays to the frame's counts (tileDispatch.w, traceCounts.x). The includer enables
// GL_KHR_shader_subgroup_basic, _vote and _arithmetic.
void addObjectWork(uint objectId, uint work) {
  uint rays = subgroupAdd(rbRays), prior = subgroupAdd(rbPriorRays);
  if (subgroupElect()) {
    atomicAdd(tileDispatch.w, rays);
    atomicAdd(traceCounts.x, prior);
  }
  bool pending = true;
  while (subgroupAny(pending)) {
    uint current = subgroupMin(pending ? objectId : RB_NO_OBJECT);
    bool mine = pending && objectId == current;
    uint sum = subgroupAdd(mine ? work : 0u);
    if (mine && subgroupElect()) atomicAdd(objectCosts[current].work, sum);
    pending = pending && !mine;
  }
}

struct HitSurface {
  vec3 position;
  vec3 geometricNormal;  // faces the incoming ray
  vec3 normal;           // shading normal, same side as geometricNormal
  vec2 uv;
  vec4 baseColor;
  float metallic;
  float roughness;
  float transmission;
  float ior;
  vec3 emissive;
  uint material;
  bool frontFace;
  Layers layers;
};

// N perturbed by the normal map in texture `slot` at a hit at `uv` on the triangle with edges
// e1, e2 and vertex texture coordinates uv0..uv2 (each taken through the map's transform).
vec3 mappedNormal(GpuMaterial m, int slot, vec3 N, float scale, vec3 e1, vec3 e2, vec2 uv0, vec2 uv1, vec2 uv2, vec2 uv) {
  vec2 t0 = textureUv(m, slot, uv0);
  return perturbNormal(N, RB_SAMPLE_MATERIAL(slot, textureUv(m, slot, uv)).xyz, scale, e1, e2, textureUv(m, slot, uv1) - t0,
                       textureUv(m, slot, uv2) - t0);
}

// Interpolated attributes of triangle `primitive` of `object` at barycentrics (b1, b2).
HitSurface hitSurface(uint object, uint primitive, vec2 bary, uint material, vec3 rayDir) {
  GpuObject o = objects[object];
  uint base = o.ids.y + primitive * 3u;
  GpuVertex v0 = vertices[o.ids.z + meshIndices[base]];
  GpuVertex v1 = vertices[o.ids.z + meshIndices[base + 1u]];
  GpuVertex v2 = vertices[o.ids.z + meshIndices[base + 2u]];
  float w0 = 1.0 - bary.x - bary.y;
  HitSurface h;
  vec3 p0 = (o.model * vec4(v0.positionU.xyz, 1.0)).xyz, p1 = (o.model * vec4(v1.positionU.xyz, 1.0)).xyz,
       p2 = (o.model * vec4(v2.positionU.xyz, 1.0)).xyz;
  h.position = w0 * p0 + bary.x * p1 + bary.y * p2;
  vec3 ng = normalize(cross(p1 - p0, p2 - p0));
  h.frontFace = dot(ng, rayDir) < 0.0;
  h.geometricNormal = h.frontFace ? ng : -ng;
  vec3 n = normalize(mat3(o.normalMatrix) * (w0 * v0.normalV.xyz + bary.x * v1.normalV.xyz + bary.y * v2.normalV.xyz));
  h.normal = dot(n, h.geometricNormal) < 0.0 ? -n : n;
  vec2 uv0 = vec2(v0.positionU.w, v0.normalV.w), uv1 = vec2(v1.positionU.w, v1.normalV.w), uv2 = vec2(v2.positionU.w, v2.normalV.w);
  h.uv = w0 * uv0 + bary.x * uv1 + bary.y * uv2;
  GpuMaterial m = materials[material];
  vec4 color = w0 * v0.color + bary.x * v1.color + bary.y * v2.color;
  h.baseColor = m.baseColorFactor * color;
  h.baseColor *= sampleMaterial(m, m.textures.x, h.uv, vec4(1.0));
  vec4 mr = sampleMaterial(m, m.textures.y, h.uv, vec4(1.0));
  h.metallic = clamp(m.metallicRoughnessTransmissionIor.x * mr.b, 0.0, 1.0);
  h.roughness = clamp(m.metallicRoughnessTransmissionIor.y * mr.g, 0.0, 1.0);
  h.transmission = m.metallicRoughnessTransmissionIor.z;
  h.ior = m.metallicRoughnessTransmissionIor.w;
  h.emissive = m.emissiveAlphaCutoff.rgb * sampleMaterial(m, m.textures.w, h.uv, vec4(1.0)).rgb;
  h.material = material;
  // The normal maps, as the G-buffer raster applies them (gbuffer.frag): the base's, and the
  // coat's on the unperturbed normal; the frame from the triangle's edges.
  vec3 surfaceN = h.normal;
  if (m.textures.z >= 0) h.normal = mappedNormal(m, m.textures.z, surfaceN, m.normalScaleThicknessFlags.x, p1 - p0, p2 - p0, uv0, uv1, uv2, h.uv);
  h.layers = materialLayers(m, h.uv, h.normal, h.ior, true);
  h.layers.clearcoatNormal = surfaceN;
  if ((materialFlags(m) & RB_MATERIAL_LAYERS) != 0u && m.layerTextures.z >= 0)
    h.layers.clearcoatNormal = mappedNormal(m, m.layerTextures.z, surfaceN, m.clearcoat.z, p1 - p0, p2 - p0, uv0, uv1, uv2, h.uv);
  return h;
}

// Alpha test of a non-opaque candidate (alpha-masked material).
bool candidateIsOpaque(RayQuery q) {
  GpuMaterial m = materials[rqCandidateMaterial(q)];
  GpuObject o = objects[rqCandidateObject(q)];
  uint base = o.ids.y + rqCandidatePrimitive(q) * 3u;
  vec2 bary = rqCandidateBarycentrics(q);
  float w0 = 1.0 - bary.x - bary.y;
  GpuVertex v0 = vertices[o.ids.z + meshIndices[base]];
  GpuVertex v1 = vertices[o.ids.z + meshIndices[base + 1u]];
  GpuVertex v2 = vertices[o.ids.z + meshIndices[base + 2u]];
  vec2 uv = w0 * vec2(v0.positionU.w, v0.normalV.w) + bary.x * vec2(v1.positionU.w, v1.normalV.w) +
            bary.y * vec2(v2.positionU.w, v2.normalV.w);
  float alpha = m.baseColorFactor.a * (w0 * v0.color.a + bary.x * v1.color.a + bary.y * v2.color.a);
  alpha *= sampleMaterial(m, m.textures.x, uv, vec4(1.0)).a;
  return alpha >= m.emissiveAlphaCutoff.w;
}

// 1 when nothing blocks the segment origin + t * dir, t in (0, tMax); alpha masks respected.
float traceVisibility(vec3 origin, vec3 dir, float tMax, inout uint work) {
  ++rbRays;
  RayQuery q;
  rqInitialize(q, RB_RQ_TERMINATE_ON_FIRST_HIT, 0xFFu, origin, 0.0, dir, tMax);
  while (rqProceed(q))
    if (candidateIsOpaque(q)) rqConfirm(q);
  uvec2 w = rqWork(q);
  work += w.x + w.y;
  return rqCommittedHit(q) ? 0.0 : 1.0;
}

// Radiance leaving a secondary-ray hit towards the ray's origin.
vec3 shadeHit(HitSurface h, vec3 V, inout uint work) {
  GpuMaterial m = materials[h.material];
  if ((floatBitsToUint(m.normalScaleThicknessFlags.z) & RB_MATERIAL_UNLIT) != 0u) return h.baseColor.rgb;
  vec3 color = h.emissive;
  vec3 origin = offsetRay(h.position, h.geometricNormal);
  for (uint i = 0u; i < frame.sizeLightsFrame.z; ++i) {
    GpuLight light = lights[i];
    vec3 L;
    float dist, scale;
    if (!lightSample(light, h.position, L, dist, scale) || dot(h.normal, L) <= 0.0) continue;
    float visible = traceVisibility(origin, L, dist, work);
    color += shadeLayered(h.normal, V, L, h.baseColor.rgb, h.metallic, h.roughness, h.transmission, h.layers) * light.colorIntensity.rgb * scale *
             visible;
  }
  vec3 irradiance = textureLod(envMap, h.normal, float(RB_ENV_MIPS - 1)).rgb;
  vec3 coat = h.layers.clearcoat > 0.0
                  ? textureLod(envMap, coatReflection(h.layers, V), h.layers.clearcoatRoughness * float(RB_ENV_MIPS - 1)).rgb
                  : vec3(0.0);
  color += ambientLight(h.baseColor.rgb, h.metallic, h.transmission, h.layers, h.normal, V, irradiance, coat);
  return color;
}

#endif
