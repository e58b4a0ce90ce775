#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_ARB_shader_clock : require
#include "include/rt_common.glsl"
#include "include/gbuffer.glsl"
#include "include/display.glsl"
#include "include/env_fallback.glsl"
#include "include/fill_history.glsl"
#include "include/item_stats.glsl"
#include "include/probe.glsl"
#include "include/rates.glsl"
#include "include/tile_fill.glsl"
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
// reduced ray rate (include/rates.glsl) traces its pixels of this frame, and the tile's
// other pixels of the item are filled from what those changed (fillPending).
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

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

// What each path traced here at a reduced rate changed against its fallback (traced minus
// fallback, the surface's weights applied), for the tile's fill (include/tile_fill.glsl); bit 0
// / 1 of fillPaths: which paths it holds.
shared vec3 fillReflection[RB_FILL_SLOTS];
shared vec3 fillRefraction[RB_FILL_SLOTS];
shared uint fillPaths[RB_FILL_SLOTS];

// The paths this pipeline holds (RB_PATHS_CONSTANT_ID): a scene without glass compiles no
// refraction, one without smooth surfaces no reflection.
layout(constant_id = RB_PATHS_CONSTANT_ID) const uint rbPaths = RB_RT_REFLECTIONS | RB_RT_REFRACTIONS;

// Whether the frame traces the surface's reflection (transmission) path where its item is
// traced: the pipeline holds it, the effect is on, and the surface is smooth enough (transmissive).
bvec2 surfacePaths(Surface s) {
  uint effects = frame.rayTracing.x;
  return bvec2((rbPaths & RB_RT_REFLECTIONS) != 0u && (effects & RB_RT_REFLECTIONS) != 0u && s.roughness <= maxTracedRoughness(),
               (rbPaths & RB_RT_REFRACTIONS) != 0u && (effects & RB_RT_REFRACTIONS) != 0u && s.transmission * (1.0 - s.metallic) > 0.0);
}

// The pixel's paths their selected items skip this frame at a reduced rate.
bvec2 pendingPaths(Surface s, Selection sel, ivec2 pixel) {
  bvec2 paths = surfacePaths(s);
  return bvec2(paths.x && itemSelected(sel, RB_ITEM_REFLECTIONS) && !rateTraces(itemRate(sel, RB_ITEM_REFLECTIONS), pixel),
               paths.y && itemSelected(sel, RB_ITEM_REFRACTIONS) && !rateTraces(itemRate(sel, RB_ITEM_REFRACTIONS), pixel));
}

// A traced neighbour as the fill reads it: its changes, the paths it holds (bits 0 and 1).
void addFillSample(float w, uint paths, vec3 reflection, vec3 refraction, bvec2 pending, inout vec3 sum[2], inout vec3 squares[2], inout vec2 weights) {
  if (w <= 0.0) return;
  if (pending.x && (paths & 1u) != 0u) {
    sum[0] += w * reflection;
    squares[0] += w * reflection * reflection;
    weights.x += w;
  }
  if (pending.y && (paths & 2u) != 0u) {
    sum[1] += w * refraction;
    squares[1] += w * refraction * refraction;
    weights.y += w;
  }
}

// The weighted mean change, shrunk towards none (the fallback) by its spread: m |m|^2 / (|m|^2 +
// variance), so neighbours that agree are filled in whole and ones that disagree (a small
// curved mirror, whose neighbours a few pixels away reflect other directions) leave the
// fallback nearly as it is, where their mean would add noise.
vec3 shrunkMean(vec3 sum, vec3 squares, float weight) {
  vec3 mean = sum / weight;
  vec3 variance = max(squares / weight - mean * mean, vec3(0.0));
  float signal = dot(mean, mean), spread = variance.x + variance.y + variance.z;
  return signal > 0.0 ? mean * (signal / (signal + spread)) : vec3(0.0);
}

// The tile's 1/16 samples with their changes (include/tile_fill.glsl's SixteenthSample).
struct EffectSample {
  SixteenthSample at;
  uint paths;
  vec3 reflection;
  vec3 refraction;
};

EffectSample effectSample(int k) {
  uint slot = RB_TILE_PIXELS + uint(k);
  return EffectSample(sixteenthSample(k), fillPaths[slot], fillReflection[slot], fillRefraction[slot]);
}

// The weighted mean change against the fallback of the tile's traced neighbours of `pixel` for
// its paths `paths` (x reflection, y refraction): `found` the paths some neighbour qualified for,
// `mean` their means. Both paths' items may run at different rates: the denser rate's neighbours
// are read (the rates nest, so they hold the sparser one's samples near the pixel), each where
// either traced. `leaveOut`: the pixel is one its rate traced (fillMiss), so its own sample is
// left out, and at 1/4 the neighbours of its phase two pixels away are read.
void fillMean(ivec2 pixel, Surface s, Selection sel, bvec2 paths, EffectSample samples[4], bool leaveOut, out vec3 mean[2], out bvec2 found) {
  FillCentre c = fillCentre(s.objectId, s.position, s.normal);
  uint rates[2] = uint[2](paths.x ? itemRate(sel, RB_ITEM_REFLECTIONS) : RB_RATE_SIXTEENTH,
                          paths.y ? itemRate(sel, RB_ITEM_REFRACTIONS) : RB_RATE_SIXTEENTH);
  uint rate = min(rates[0], rates[1]);  // the denser of the two (the codes grow as the rate falls)
  vec3 sum[2] = vec3[2](vec3(0.0), vec3(0.0)), squares[2] = vec3[2](vec3(0.0), vec3(0.0));
  vec2 weights = vec2(0.0);
  if (rate == RB_RATE_SIXTEENTH) {
    ivec2 here = pixel & (RB_TILE_SIZE - 1);
    for (int k = 0; k < 4; ++k)
      if (!leaveOut || samples[k].at.at != here)
        addFillSample(sixteenthWeight(c, samples[k].at, pixel), samples[k].paths, samples[k].reflection, samples[k].refraction, paths, sum, squares, weights);
  } else {
    for (int k = 0; k < 9; ++k) {
      uint slot;
      float w = leaveOut && k == 4 ? 0.0 : fillWeight(c, rate, pixel, (leaveOut ? 2 : 1) * fillOffset(k), slot);
      if (w > 0.0) addFillSample(w, fillPaths[slot], fillReflection[slot], fillRefraction[slot], paths, sum, squares, weights);
    }
  }
  found = bvec2(weights.x >= RB_FILL_MIN_WEIGHT, weights.y >= RB_FILL_MIN_WEIGHT);
  mean = vec3[2](found.x ? shrunkMean(sum[0], squares[0], weights.x) : vec3(0.0), found.y ? shrunkMean(sum[1], squares[1], weights.y) : vec3(0.0));
}

// Fills the paths pending at `pixel` from the tile's traced neighbours: their weighted mean
// change against the fallback is added to this pixel's fallback (reflectionImage,
// refractionImage). Filling the
// change rather than the radiance keeps this pixel's own environment where the neighbours'
// rays escaped to it, and spares each filled pixel its weights and environment lookups (which
// cost about as much as the fill's gather on lavapipe).
void fillPending(ivec2 pixel, Surface s, Selection sel, bvec2 pending, EffectSample samples[4]) {
  vec3 mean[2];
  bvec2 found;
  fillMean(pixel, s, sel, pending, samples, false, mean, found);
  if (found.x) imageStore(reflectionImage, pixel, vec4(imageLoad(reflectionImage, pixel).rgb + mean[0], 1.0));
  if (found.y) imageStore(refractionImage, pixel, vec4(imageLoad(refractionImage, pixel).rgb + mean[1], 1.0));
}

// With RB_RT_MEASURE_FILL, at a pixel a reduced rate traced, the display error its fill would
// have left had the rate skipped it, per path (x reflection, y refraction), against the
// fallback's (the item's error): each item learns its fill's quality from the two
// (GpuItemCost::fillQualitySixteenth, fillQualityQuarter). The fill's prediction here follows
// the fill's order: what the temporal fill carries to the point (the change traced a rate period
// ago: the oldest a skipped pixel carries), else the mean change of the tile's other traced
// pixels on the object around it (fillMean: 1/16's other three samples, 1/4's eight of the same
// phase two pixels away; farther than the fill reads for a skipped pixel, so the estimate errs
// low), else none (the fallback).
vec2 fillMiss(ivec2 pixel, Surface s, Selection sel, bvec2 shown, vec3 change[2], vec3 untraced, EffectSample samples[4], out bvec2 measured) {
  uint rates[2] = uint[2](itemRate(sel, RB_ITEM_REFLECTIONS), itemRate(sel, RB_ITEM_REFRACTIONS));
  measured = bvec2(shown.x && (rates[0] == RB_RATE_QUARTER || rates[0] == RB_RATE_SIXTEENTH),
                   shown.y && (rates[1] == RB_RATE_QUARTER || rates[1] == RB_RATE_SIXTEENTH));
  if (!any(measured)) return vec2(0.0);
  vec3 predicted[2] = vec3[2](vec3(0.0), vec3(0.0));
  bvec2 open = measured;
  if (temporalFill()) {
    History h = previousHistory(s.position, s.objectId);
    bvec2 carried = bvec2(open.x && historyPredicts(h.age.x, h.turn.x, rates[0]),
                          open.y && historyPredicts(h.age.y, h.turn.y, rates[1]));
    predicted = vec3[2](carried.x ? h.change[0] : vec3(0.0), carried.y ? h.change[1] : vec3(0.0));
    open = bvec2(open.x && !carried.x, open.y && !carried.y);
  }
  if (any(open)) {
    vec3 mean[2];
    bvec2 found;
    fillMean(pixel, s, sel, open, samples, true, mean, found);
    if (found.x) predicted[0] = mean[0];  // (found only on open paths: fillMean reads no other)
    if (found.y) predicted[1] = mean[1];
  }
  return vec2(measured.x ? displayError(untraced + predicted[0], untraced + change[0]) : 0.0,
              measured.y ? displayError(untraced + predicted[1], untraced + change[1]) : 0.0);
}

// `shown`: the paths traced and shown here, with what they changed against the fallback in `change`.
void traceEffects(ivec2 pixel, bool lit, Surface s, Selection sel, out bvec2 shown, out vec3 change[2], out vec3 untraced) {
  shown = bvec2(false);
  change = vec3[2](vec3(0.0), vec3(0.0));
  untraced = vec3(0.0);
  if (!lit) return;
  // Per path: whether its item is probed here rather than selected.
  bool probed[2] = bool[2](!itemSelected(sel, RB_ITEM_REFLECTIONS) && itemProbed(sel, RB_ITEM_REFLECTIONS, pixel),
                           !itemSelected(sel, RB_ITEM_REFRACTIONS) && itemProbed(sel, RB_ITEM_REFRACTIONS, pixel));
  uint rates[2] = uint[2](itemRate(sel, RB_ITEM_REFLECTIONS), itemRate(sel, RB_ITEM_REFRACTIONS));
  bvec2 paths = surfacePaths(s);
  bool reflects = paths.x && ((itemSelected(sel, RB_ITEM_REFLECTIONS) && rateTraces(rates[0], pixel)) || probed[0]);
  bool refracts = paths.y && ((itemSelected(sel, RB_ITEM_REFRACTIONS) && rateTraces(rates[1], pixel)) || probed[1]);
  if (!reflects && !refracts) return;  // the environment fallback stands
  rbPriorRays = (reflects ? priorRays(RB_ITEM_REFLECTIONS) : 0u) + (refracts ? priorRays(RB_ITEM_REFRACTIONS) : 0u);
  uint start = clockNow();
  vec3 p, ng;
  readExactSurface(pixel, p, ng);
  vec3 N, V, specularWeight, transmitWeight;
  tracedPathWeights(s, p, ng, N, V, specularWeight, transmitWeight);
  uint depth = clamp(frame.rayTracing.y, 1u, uint(RB_RT_MAX_DEPTH));
  vec3 R = reflect(-V, N);
  if (dot(R, ng) < 0.0) R = reflect(R, ng);  // a normal map tilted the mirror ray below the surface
  // The fallback's paths, as the env_fallback pass computed them.
  vec3 rasterV = normalize(frame.cameraPositionNear.xyz - s.position);
  vec3 fallback[2] = vec3[2](envReflection(s, rasterV, pixel), envTransmission(s, rasterV));
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
    color[path] = traceRadiance(origin, dir, depth, work[path]) * absorbed * (path == 0 ? specularWeight : transmitWeight);
    pathTicks[path] = clockNow() - pathStart;
  }
  if (reflects && !probed[0]) imageStore(reflectionImage, pixel, vec4(color[0], 1.0));
  if (refracts && !probed[1]) imageStore(refractionImage, pixel, vec4(color[1], 1.0));
  shown = bvec2(reflects && !probed[0], refracts && !probed[1]);
  change = vec3[2](color[0] - fallback[0], color[1] - fallback[1]);
  markTraced(pixel, (reflects && !probed[0] ? RB_RT_REFLECTIONS : 0u) | (refracts && !probed[1] ? RB_RT_REFRACTIONS : 0u));
  // For the tile's fill: the paths traced here at a reduced rate.
  bool shared0 = reflects && !probed[0] && rates[0] != RB_RATE_FULL, shared1 = refracts && !probed[1] && rates[1] != RB_RATE_FULL;
  if (shared0 || shared1) {
    uvec2 slots = fillSlots(pixel);
    shareFillSource(slots, s.objectId, s.position, s.normal);  // (the filled pixel's centre is its s.position too)
    for (int n = 0; n < 2; ++n) {
      fillPaths[slots[n]] = (shared0 ? 1u : 0u) | (shared1 ? 2u : 0u);
      fillReflection[slots[n]] = color[0] - fallback[0];
      fillRefraction[slots[n]] = color[1] - fallback[1];
    }
  }
  addObjectWork(s.objectId, (probed[0] ? 0u : work[0]) + (probed[1] ? 0u : work[1]));
  if (measuringItems()) {
    untraced = imageLoad(directImage, pixel).rgb + fallback[0] + fallback[1];
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
    addItemCounts(s.objectId, uvec3(0u, work[0], work[1]), uvec3(0u, ticks), vec3(0.0, reflectionError, refractionError), counted);
  }
}

// Which of the pixel's paths (x reflection, y transmission) its items trace here this frame
// (selected and traced at their rate, or probed), and which a reduced rate leaves to the fill.
void pathsHere(Selection sel, ivec2 pixel, out bvec2 traced, out bvec2 skipped) {
  bvec2 selected = bvec2(itemSelected(sel, RB_ITEM_REFLECTIONS), itemSelected(sel, RB_ITEM_REFRACTIONS));
  bvec2 rateHere = bvec2(itemTracedHere(sel, RB_ITEM_REFLECTIONS, pixel), itemTracedHere(sel, RB_ITEM_REFRACTIONS, pixel));
  traced = bvec2((selected.x && rateHere.x) || (!selected.x && itemProbed(sel, RB_ITEM_REFLECTIONS, pixel)),
                 (selected.y && rateHere.y) || (!selected.y && itemProbed(sel, RB_ITEM_REFRACTIONS, pixel)));
  skipped = bvec2(selected.x && !rateHere.x, selected.y && !rateHere.y);
}

void main() {
  ivec2 pixel = tilePixel(RB_EFFECT_TILES);
  bool fills = fillsInPass();
  uint begun = clockNow();
  if (fills) clearFillSlot(pixel);
  // A pixel whose items trace nothing here reads no more of the G-buffer than its object (and,
  // where a reduced rate skipped it, what its fill needs: readFillSurface).
  Surface s;
  bvec2 pending = bvec2(false), shown = bvec2(false);
  vec3 change[2] = vec3[2](vec3(0.0), vec3(0.0)), untraced = vec3(0.0);
  uint objectId = all(lessThan(uvec2(pixel), frame.sizeLightsFrame.xy)) ? texelFetch(gObjectId, pixel, 0).r : RB_NO_OBJECT;
  Selection sel = selectionAt(objectId, pixel);
  bool tracedAny = false;
  if (objectId != RB_NO_OBJECT) {
    bvec2 traced, skipped;
    pathsHere(sel, pixel, traced, skipped);
    tracedAny = any(traced);
    if (tracedAny) {
      bool lit = readSurface(pixel, s) && !s.unlit;
      traceEffects(pixel, lit, s, sel, shown, change, untraced);
      if (lit) pending = pendingPaths(s, sel, pixel);
    } else if (fills && any(skipped) && readFillSurface(pixel, objectId, s)) {
      pending = pendingPaths(s, sel, pixel);
    }
  }
  if (!fills) return;
  // A pixel whose items' reduced rates skipped it is timed for their cost per skipped pixel
  // (GpuItemCost::fillPerPixel): its surface read before the barrier, where no lane of its
  // subgroup traced (a tracing lane's span is the subgroup's), and its fill after it.
  bvec2 skippedPaths = pending;
  uint before = subgroupAny(tracedAny) ? 0u : clockNow() - begun;
  barrier();
  uint resumed = clockNow();
  EffectSample samples[4] = EffectSample[4](effectSample(0), effectSample(1), effectSample(2), effectSample(3));
  // The fill's miss where a reduced rate traced, timed apart: its span is the traced paths' cost.
  uint missBegun = clockNow();
  bvec2 missed = bvec2(false);
  vec2 miss = (frame.rayTracing.w & RB_RT_MEASURE_FILL) != 0u && any(shown) ? fillMiss(pixel, s, sel, shown, change, untraced, samples, missed) : vec2(0.0);
  uint missSpan = clockNow() - missBegun;
  uvec2 age = uvec2(shown.x ? 0u : RB_HISTORY_NONE, shown.y ? 0u : RB_HISTORY_NONE), turn = uvec2(0u);
  if (temporalFill() && any(pending)) {
    // The pending paths still valid where the previous frame saw the point add what tracing
    // changed against the fallback there to this frame's fallback (which follows the view, as
    // the spatial fill does); the others fill from traced neighbours.
    History h = previousHistory(s.position, s.objectId);
    bvec2 carried = bvec2(pending.x && historyFits(h.age.x, h.turn.x, itemRate(sel, RB_ITEM_REFLECTIONS)),
                          pending.y && historyFits(h.age.y, h.turn.y, itemRate(sel, RB_ITEM_REFRACTIONS)));
    if (carried.x) imageStore(reflectionImage, pixel, vec4(imageLoad(reflectionImage, pixel).rgb + h.change[0], 1.0));
    if (carried.y) imageStore(refractionImage, pixel, vec4(imageLoad(refractionImage, pixel).rgb + h.change[1], 1.0));
    change = vec3[2](carried.x ? h.change[0] : change[0], carried.y ? h.change[1] : change[1]);
    age = uvec2(carried.x ? h.age.x + 1u : age.x, carried.y ? h.age.y + 1u : age.y);
    turn = uvec2(carried.x ? h.turn.x : 0u, carried.y ? h.turn.y : 0u);
    pending = bvec2(pending.x && !carried.x, pending.y && !carried.y);
  }
  if (any(pending)) fillPending(pixel, s, sel, pending, samples);
  if (temporalFill() && any(notEqual(age, uvec2(RB_HISTORY_NONE)))) writeHistory(pixel, change, age, turn, s.objectId, s.position);
  if (measuringItems()) {
    // Shared among the subgroup's skipped pixels, each one's split over the paths it skipped;
    // the miss's span among the traced pixels that measured it, added to their paths' ticks.
    bool skipped = any(skippedPaths);
    uint share = clockShare(0u, before + (clockNow() - resumed - missSpan), subgroupAdd(skipped ? 1u : 0u));
    uvec2 paths = uvec2(skippedPaths), measured = uvec2(missed);
    uint each = share / max(paths.x + paths.y, 1u);
    uint missEach = clockShare(0u, missSpan, subgroupAdd(any(missed) ? 1u : 0u)) / max(measured.x + measured.y, 1u);
    addItemCounts(skipped || any(missed) ? s.objectId : RB_NO_OBJECT, uvec3(0u), uvec3(0u, measured * missEach), vec3(0.0), uvec3(0u),
                  uvec3(0u, paths * each), uvec3(0u, paths), vec3(0.0, miss));
  }
}
