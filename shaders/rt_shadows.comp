#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_ARB_shader_clock : require
#include "include/rt_common.glsl"
#include "include/gbuffer.glsl"
#include "include/item_stats.glsl"
#include "include/shadows.glsl"
#include "include/probe.glsl"
#include "include/rates.glsl"
#include "include/tile_fill.glsl"

// Ray-traced shadows: one any-hit ray per light from the exact surface point (offset along
// the geometric normal), alpha masks respected, for the pixels of objects whose shadow item
// is selected. With RB_RT_CLASSIFY_SHADOWS a light whose shadow map is certain at the pixel
// (include/shadows.glsl's classifier) keeps the map's visibility and traces no ray; with
// RB_RT_SHORTEN_SHADOW_RAYS a ray ends just past the nearest blocker the map holds around it
// (include/shadows.glsl's shadowRayEnd). Writes
// each light's visibility into its layer of the shadow mask, which the lighting pass uses
// instead of the shadow maps. Where the probe traces a left-out shadow item, the mask is
// written for the lighting pass to measure, which still shows the shadow maps there.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

// Each light's correction of the shadow map at each traced pixel of the tile for the fill
// (include/tile_fill.glsl): the traced visibility minus the map's there, a byte per light
// (-1..1 as 0..254; a traced pixel writes every light; the fill reads only the slots of traced
// pixels on its object).
shared uint fillLights[RB_FILL_SLOTS * (RB_MAX_LIGHTS / 4)];

uint correctionByte(float correction) { return uint(round((clamp(correction, -1.0, 1.0) + 1.0) * 127.0)); }

float fillCorrection(uint slot, uint light) {
  uint byte = (fillLights[slot * (RB_MAX_LIGHTS / 4) + light / 4u] >> (8u * (light & 3u))) & 0xFFu;
  return float(byte) / 127.0 - 1.0;
}

// Traces the pixel's shadow rays and shares them for the tile's fill. A pixel its item's
// reduced rate skips this frame reads only what its fill needs (gbuffer.glsl's readFillSurface) and
// runs no light loop, classifier or counters before the barrier: on lavapipe those cost about
// as much per pixel as a quarter rate's rays, so a skipped pixel that ran them made a rate
// save little. `skipped` returns that pixel's fill centre (object RB_NO_OBJECT: nothing to fill)
// and `sel` its object's selection.
// Returns whether its rate traces the pixel here (an unlit surface then traces nothing).
bool traceShadows(ivec2 pixel, bool fills, out FillCentre skipped, out Selection sel) {
  sel = Selection(0u);
  skipped.objectId = RB_NO_OBJECT;
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return false;
  uint objectId = texelFetch(gObjectId, pixel, 0).r;
  if (objectId == RB_NO_OBJECT) return false;
  sel = selectionAt(objectId, pixel);
  bool probe = !itemSelected(sel, RB_ITEM_SHADOWS);
  if (probe && !itemProbed(sel, RB_ITEM_SHADOWS, pixel)) return false;  // the lighting pass reads no mask there
  uint rate = probe ? RB_RATE_FULL : itemRate(sel, RB_ITEM_SHADOWS);
  bool share = fills && rate != RB_RATE_FULL;
  Surface s;
  if (!rateTraces(rate, pixel)) {
    if (readFillSurface(pixel, objectId, s)) skipped = fillCentre(objectId, s.position, s.normal);
    return false;
  }
  if (!readSurface(pixel, s) || s.unlit) return true;
  uint start = clockNow();
  vec3 p, ng;
  readExactSurface(pixel, p, ng);
  vec3 origin = offsetRay(p, ng);
  bool classify = (frame.rayTracing.w & RB_RT_CLASSIFY_SHADOWS) != 0u;
  bool shorten = (frame.rayTracing.w & RB_RT_SHORTEN_SHADOW_RAYS) != 0u;
  uint work = 0u, word = 0u;
  uvec2 slots = fillSlots(pixel);
  bool traced = false;  // some light's ray was traced here
  rbPriorRays = priorRays(RB_ITEM_SHADOWS);
  // Lights the classifier finds certain need no ray.
  for (uint i = 0u; i < frame.sizeLightsFrame.z; ++i) {
    vec3 L;
    float dist, scale;
    float visible = 0.0, mapped = 0.0;
    if (lightSample(lights[i], p, L, dist, scale) && dot(s.normal, L) > 0.0) {
      if (classify && shadowMapCertain(lights[i], s.position, s.normal, frame.exposure.y, mapped)) visible = mapped;
      else {
        if (share && !classify) mapped = shadowFromLight(lights[i], s.position, s.normal);
        visible = traceVisibility(origin, L, shorten ? shadowRayEnd(lights[i], origin, L, dist) : dist, work);
        traced = true;
      }
    }
    imageStore(shadowMask, ivec3(pixel, int(i)), vec4(visible));
    if (share) {
      word |= correctionByte(visible - mapped) << (8u * (i & 3u));
      if ((i & 3u) == 3u || i + 1u == frame.sizeLightsFrame.z) {
        for (int n = 0; n < 2; ++n) fillLights[slots[n] * (RB_MAX_LIGHTS / 4) + i / 4u] = word;
        word = 0u;
      }
    }
  }
  if (share) shareFillSource(slots, s.objectId, p, s.normal);
  if (traced && !probe) markTraced(pixel, RB_RT_SHADOWS);
  uint ticks = clockShare(start, clockNow(), subgroupAdd(1u));
  addObjectWork(s.objectId, probe ? 0u : work);  // (the per-object cost model learns from selected pixels)
  // The pixels a probe or a reduced rate traced are counted here (a full rate's at selection).
  bool counted = probe || rate != RB_RATE_FULL;
  if (measuringItems()) addItemCounts(s.objectId, uvec3(work, 0u, 0u), uvec3(ticks, 0u, 0u), vec3(0.0), uvec3(counted ? 1u : 0u, 0u, 0u));
  return true;
}

// Fills a skipped pixel's lights: per light facing it, the shadow map's visibility there
// corrected by the weighted mean of the map's error at the pixels around it that its item
// traced this frame (0 where the classifier found the map certain), else the map's alone.
// Filling the correction, not the visibility, keeps the map's shadow edges at the map's
// resolution where the rays agree with it, where a filled visibility makes every edge a
// staircase of the rate's blocks. Where there is nothing to correct (most pixels: the
// neighbours' maps were certain or right) the mask says "the map's" (negative) and the
// lighting pass, which looks the map up for untraced items anyway, does it outside the
// ray-tracing stage: the lookup was most of a skipped pixel's cost.
void fillPending(ivec2 pixel, FillCentre c, Selection sel, SixteenthSample samples[4]) {
  float weights[9];
  uint slots[9];
  uint rate = itemRate(sel, RB_ITEM_SHADOWS);
  bool sixteenth = rate == RB_RATE_SIXTEENTH;
  int candidates = sixteenth ? 4 : 9;
  for (int k = 0; k < candidates; ++k) {
    if (sixteenth) {
      weights[k] = sixteenthWeight(c, samples[k], pixel);
      slots[k] = RB_TILE_PIXELS + uint(k);
    } else weights[k] = fillWeight(c, rate, pixel, fillOffset(k), slots[k]);
  }
  for (uint i = 0u; i < frame.sizeLightsFrame.z; ++i) {
    vec3 L;
    float dist, scale;
    float visible = 0.0;
    if (lightSample(lights[i], c.position, L, dist, scale) && dot(c.normal, L) > 0.0) {
      float sum = 0.0, weight = 0.0;
      for (int k = 0; k < candidates; ++k) {
        if (weights[k] <= 0.0) continue;
        sum += weights[k] * fillCorrection(slots[k], i);
        weight += weights[k];
      }
      float correction = weight >= RB_FILL_MIN_WEIGHT ? sum / weight : 0.0;
      visible = correction != 0.0 ? clamp(shadowFromLight(lights[i], c.position, c.normal) + correction, 0.0, 1.0) : -1.0;
    }
    imageStore(shadowMask, ivec3(pixel, int(i)), vec4(visible));
  }
}

void main() {
  ivec2 pixel = tilePixel(RB_SHADOW_TILES);
  bool fills = fillsInPass();
  uint begun = clockNow();
  if (fills) clearFillSlot(pixel);
  FillCentre skipped;
  Selection sel;
  bool traced = traceShadows(pixel, fills, skipped, sel);
  if (!fills) return;
  // A pixel its item's reduced rate skipped is timed as in rt_effects.comp: its surface read
  // where no lane of its subgroup traced, and its fill.
  uint before = subgroupAny(traced) ? 0u : clockNow() - begun;
  barrier();
  uint resumed = clockNow();
  SixteenthSample samples[4] = SixteenthSample[4](sixteenthSample(0), sixteenthSample(1), sixteenthSample(2), sixteenthSample(3));
  bool pending = skipped.objectId != RB_NO_OBJECT;
  if (pending) fillPending(pixel, skipped, sel, samples);
  if (measuringItems()) {
    uint share = clockShare(0u, before + (clockNow() - resumed), subgroupAdd(pending ? 1u : 0u));
    addItemCounts(skipped.objectId, uvec3(0u), uvec3(0u), vec3(0.0), uvec3(0u), uvec3(pending ? share : 0u, 0u, 0u), uvec3(pending ? 1u : 0u, 0u, 0u), vec3(0.0));
  }
}
