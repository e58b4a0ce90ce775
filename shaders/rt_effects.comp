#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_ARB_shader_clock : require
#extension GL_EXT_shader_realtime_clock : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "include/rt_common.glsl"
#include "include/gbuffer.glsl"
#include "include/display.glsl"
#include "include/env_fallback.glsl"
#include "include/item_stats.glsl"
#include "include/probe.glsl"
#include "include/rates.glsl"
#include "include/deadline_cut.glsl"
#include "include/effect_fill.glsl"
#include "include/trace_radiance.glsl"

// Ray-traced reflections and refractions. Mirror-like surfaces (roughness up to the
// frame's cut-off, RayTracingSettings::maxRoughness) trace a closest-hit reflection ray, shaded with direct light (and
// its own shadow rays), emissive and the environment, for up to frame.rayTracing.y
// bounces along mirrors. Transmissive surfaces trace through: thin walls (no volume)
// straight on; volumes refract in (Snell, glTF IOR), travel to the exit with Beer-Lambert
// attenuation (KHR_materials_volume), reflect internally on total internal reflection and
// refract out. Fresnel splits reflection and transmission. Each path is traced where its
// item (the object's reflections, its refractions) is selected, the other keeps the
// environment fallback (include/env_fallback.glsl); replaces the fallback's result in
// reflectionImage or refractionImage for the pixels it traces. With RB_RT_MEASURE_ITEMS each traced path adds its
// work and the display-space difference it made against the fallback to its item. A path whose
// item the probe traces here (include/probe.glsl) is measured and not shown. An item at a
// reduced ray rate (include/rates.glsl) traces its pixels of this frame and writes what it
// changed to the fill's history; fill_effects.comp fills the others from it (include/effect_fill.glsl).
// Past the stage's deadline (include/stage_clock.glsl) a subgroup traces nothing and leaves its
// pixels their fallbacks (the fill finds no history of this frame there).
layout(local_size_x = RB_TRACE_GROUP_SIZE) in;

// The ray that carries light through the surface at p towards the viewer: for a thin wall
// the view ray continued behind the surface, for a volume the refracted ray after its way
// through (internal reflections included), with the volume's absorption. False when the
// light is trapped (internal reflections beyond the depth bound).
bool transmittedRay(vec3 p, vec3 ng, vec3 V, vec3 n, float ior, uint materialId, out vec3 origin, out vec3 dir, out vec3 absorbed,
                    inout uint work) {
  GpuMaterial m = materials[materialId];
  float thickness = m.normalScaleThicknessFlags.y;
  absorbed = vec3(1.0);
  origin = offsetRay(p, -ng);
  dir = -V;
  if (thickness <= 0.0) return true;  // thin wall
  vec3 T = refract(-V, n, 1.0 / max(ior, 1.0));
  if (dot(T, T) == 0.0) return false;
  for (int inside = 0; inside < RB_RT_MAX_DEPTH; ++inside) {
    RayQuery q;
    if (!traceClosest(origin, T, q, work)) {  // an open mesh: the ray leaves as it is
      dir = T;
      return true;
    }
    HitSurface h = hitSurface(rqCommittedObject(q), rqCommittedPrimitive(q), rqCommittedBarycentrics(q), rqCommittedMaterial(q), T);
    float travelled = rqCommittedT(q) * length(T);
    if (m.attenuationColorDistance.w > 0.0) absorbed *= pow(m.attenuationColorDistance.rgb, vec3(travelled / m.attenuationColorDistance.w));
    vec3 E = refract(T, h.normal, max(ior, 1.0));
    if (dot(E, E) == 0.0) {  // total internal reflection: stay inside
      T = reflect(T, h.normal);
      origin = offsetRay(h.position, h.geometricNormal);
      continue;
    }
    origin = offsetRay(h.position, -h.geometricNormal);
    dir = E;
    return true;
  }
  return false;
}

// The paths this pipeline holds (RB_PATHS_CONSTANT_ID): a scene without glass compiles no
// refraction, one without smooth surfaces no reflection.
layout(constant_id = RB_PATHS_CONSTANT_ID) const uint rbPaths = RB_RT_REFLECTIONS | RB_RT_REFRACTIONS;

// `here`: the paths its items trace at this pixel this frame (pathsHere).
void traceEffects(ivec2 pixel, Surface s, Selection sel, bvec2 here) {
  // Per path: whether its item is probed here rather than selected.
  bool probed[2] = bool[2](!itemSelected(sel, RB_ITEM_REFLECTIONS) && itemProbed(sel, RB_ITEM_REFLECTIONS, pixel),
                           !itemSelected(sel, RB_ITEM_REFRACTIONS) && itemProbed(sel, RB_ITEM_REFRACTIONS, pixel));
  uint rates[2] = uint[2](itemRate(sel, RB_ITEM_REFLECTIONS), itemRate(sel, RB_ITEM_REFRACTIONS));
  bvec2 paths = surfacePaths(s, rbPaths);
  bool reflects = paths.x && here.x, refracts = paths.y && here.y;
  if (!reflects && !refracts) return;  // the environment fallback stands
  rbPriorRays = (reflects ? priorRays(RB_ITEM_REFLECTIONS) : 0u) + (refracts ? priorRays(RB_ITEM_REFRACTIONS) : 0u);
  uint start = clockNow();
  vec3 p, ng;
  readExactSurface(pixel, p, ng);
  vec3 N, V, specularWeight, transmitWeight;
  tracedPathWeights(s, p, ng, N, V, specularWeight, transmitWeight);
  uint depth = clamp(frame.rayTracing.y, 1u, uint(RB_RT_MAX_DEPTH));
  vec3 R = mirrorDirection(V, N, ng);
  // The fallback's paths as the lighting pass wrote them, which the frame shows where a path is
  // not traced: read, not computed again (which took this pass to 0.86-0.95 of its time on the
  // court and ClearCoatTest on lavapipe).
  vec3 fallback[2] = vec3[2](imageLoad(reflectionImage, pixel).rgb, imageLoad(refractionImage, pixel).rgb);
  // Path 0 reflects, path 1 transmits; one traceRadiance call site keeps the shader (and
  // its compile time on lavapipe) half the size.
  vec3 color[2] = fallback;
  uint work[2] = uint[2](0u, 0u);
  uint pathTicks[2] = uint[2](0u, 0u);  // each path's span on the clock
  for (int path = 0; path < 2; ++path) {
    if (!(path == 0 ? reflects : refracts)) continue;
    uint pathStart = clockNow();
    vec3 origin = offsetRay(p, ng), dir = R, absorbed = vec3(1.0);
    color[path] = vec3(0.0);
    if (path == 1 && !transmittedRay(p, ng, V, N, s.ior, s.materialId, origin, dir, absorbed, work[path])) continue;
    color[path] = traceRadiance(origin, dir, path == 0 ? s.roughness : 0.0, depth, work[path]) * absorbed * (path == 0 ? specularWeight : transmitWeight);
    pathTicks[path] = clockNow() - pathStart;
  }
  if (reflects && !probed[0]) imageStore(reflectionImage, pixel, vec4(color[0], 1.0));
  if (refracts && !probed[1]) imageStore(refractionImage, pixel, vec4(color[1], 1.0));
  bvec2 shown = bvec2(reflects && !probed[0], refracts && !probed[1]);
  vec3 change[2] = vec3[2](color[0] - fallback[0], color[1] - fallback[1]);
  markTraced(pixel, (shown.x ? RB_RT_REFLECTIONS : 0u) | (shown.y ? RB_RT_REFRACTIONS : 0u));
  // What the shown paths changed, for the fill (fill_effects.comp): its spatial sources where a rate is
  // reduced, and with the temporal fill what a later frame carries where the item's rate drops.
  if (any(shown) && (temporalFill() || (shown.x && rates[0] != RB_RATE_FULL) || (shown.y && rates[1] != RB_RATE_FULL)))
    writeHistory(pixel, change, uvec2(shown.x ? 0u : RB_HISTORY_NONE, shown.y ? 0u : RB_HISTORY_NONE), uvec2(0u), s.objectId, s.position, s.normal);
  addObjectWork(s.objectId, (probed[0] ? 0u : work[0]) + (probed[1] ? 0u : work[1]));
  if (measuringItems()) {
    vec3 untraced = imageLoad(directImage, pixel).rgb + fallback[0] + fallback[1];
    float reflectionError = reflects ? displayError(untraced + change[0], untraced) : 0.0;
    float refractionError = refracts ? displayError(untraced + change[1], untraced) : 0.0;
    // Each path is charged its span shared among the lanes that traced it, and the rest of
    // the invocation (setup, fallback, measurement) shared among all, split over the lane's paths.
    uint rest = clockNow() - start - subgroupMax(pathTicks[0]) - subgroupMax(pathTicks[1]);
    uint reflectors = subgroupAdd(reflects ? 1u : 0u), refractors = subgroupAdd(refracts ? 1u : 0u), lanes = subgroupAdd(1u);
    uint own = clockShare(0u, rest, lanes * (reflects && refracts ? 2u : 1u));
    uvec2 ticks = uvec2(reflects ? clockShare(0u, pathTicks[0], reflectors) + own : 0u, refracts ? clockShare(0u, pathTicks[1], refractors) + own : 0u);
    // The pixels a probe or a reduced rate traced are counted here (a full rate's at selection).
    uvec3 counted = uvec3(0u, reflects && (probed[0] || rates[0] != RB_RATE_FULL) ? 1u : 0u, refracts && (probed[1] || rates[1] != RB_RATE_FULL) ? 1u : 0u);
    addItemCounts(s.objectId, uvec3(0u, work[0], work[1]), uvec3(0u, ticks), errorUnits(vec3(0.0, reflectionError, refractionError), pixel), counted);
  }
}

// Which of the pixel's paths (x reflection, y transmission) its items trace here this frame
// (selected and traced at their rate, or probed).
bvec2 pathsHere(Selection sel, ivec2 pixel) {
  bvec2 selected = bvec2(itemSelected(sel, RB_ITEM_REFLECTIONS), itemSelected(sel, RB_ITEM_REFRACTIONS));
  bvec2 rateHere = bvec2(itemTracedHere(sel, RB_ITEM_REFLECTIONS, pixel), itemTracedHere(sel, RB_ITEM_REFRACTIONS, pixel));
  return bvec2((selected.x && rateHere.x) || (!selected.x && itemProbed(sel, RB_ITEM_REFLECTIONS, pixel)),
               (selected.y && rateHere.y) || (!selected.y && itemProbed(sel, RB_ITEM_REFRACTIONS, pixel)));
}

// Past the deadline: the paths the pixel would have traced keep the fallback, and what the stage
// learns does without them (include/deadline_cut.glsl's leavePixel).
void leaveEffects(ivec2 pixel, uint objectId, Selection sel, bvec2 here) {
  // The channels that decide the paths, not the whole surface (two fetches of seven, and no
  // layers): past the deadline, a pixel's leave-out is time the stage spends past T.
  Surface s;
  s.objectId = objectId;
  if (!readEffectChannels(pixel, s)) return;  // unlit: traced nothing
  bvec2 paths = surfacePaths(s, rbPaths);
  bool reflects = paths.x && here.x, refracts = paths.y && here.y;
  bvec3 full = bvec3(false);
  float work = 0.0;
  for (int path = 0; path < 2; ++path) {
    uint item = path == 0 ? RB_ITEM_REFLECTIONS : RB_ITEM_REFRACTIONS, rate = itemRate(sel, item);
    bool selected = (path == 0 ? reflects : refracts) && itemSelected(sel, item);
    full[item] = selected && rate == RB_RATE_FULL;
    if (selected) work += predictedPixelWork(objectId, item, rate);
  }
  leavePixel(objectId, reflects || refracts, full, work, false);
}

void main() {
  stampEffectsStart();
  bool cut = pastDeadline(true);
  ivec2 pixel = chunkPixel(RB_EFFECT_CHUNKS);
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  // A pixel whose items trace nothing here reads no more of the G-buffer than its object.
  uint objectId = texelFetch(gObjectId, pixel, 0).r;
  if (objectId == RB_NO_OBJECT) return;
  Selection sel = selectionAt(objectId, pixel);
  bvec2 here = pathsHere(sel, pixel);
  if (!any(here)) return;  // fill_effects.comp fills what a reduced rate skipped here
  if (cut) {
    leaveEffects(pixel, objectId, sel, here);
    return;
  }
  Surface s;
  if (!readSurface(pixel, s) || s.unlit) return;
  traceEffects(pixel, s, sel, here);
}
