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
#include "include/item_stats.glsl"
#include "include/shadows.glsl"
#include "include/probe.glsl"
#include "include/rates.glsl"
#include "include/deadline_cut.glsl"

// Ray-traced shadows: one any-hit ray per light from the exact surface point (offset along
// the geometric normal), alpha masks respected, for the pixels of objects whose shadow item
// is selected. With RB_RT_CLASSIFY_SHADOWS a light whose shadow map is certain at the pixel
// (include/shadows.glsl's classifier) keeps the map's visibility and traces no ray; with
// RB_RT_SHORTEN_SHADOW_RAYS a ray ends just past the nearest blocker the map holds around it
// (include/shadows.glsl's shadowRayEnd). Writes each light's visibility into its layer of the
// shadow mask, which the lighting pass uses instead of the shadow maps, and where the item's
// reduced rate traced the pixel, the map's visibility there into the light's second layer: the
// lighting pass fills the pixels the rate skipped from the map's error at the traced ones
// (include/shadow_fill.glsl), so a skipped pixel costs this pass no more than reading its
// object. Where the probe traces a left-out shadow item, the mask is written for the lighting
// pass to measure, which still shows the shadow maps there. Past the stage's deadline
// (include/stage_clock.glsl) a subgroup traces nothing and leaves its pixels to the maps.
layout(local_size_x = RB_TRACE_GROUP_SIZE) in;

void traceShadows(ivec2 pixel) {
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  uint objectId = texelFetch(gObjectId, pixel, 0).r;
  if (objectId == RB_NO_OBJECT) return;
  Selection sel = selectionAt(objectId, pixel);
  bool probe = !itemSelected(sel, RB_ITEM_SHADOWS);
  if (probe && !itemProbed(sel, RB_ITEM_SHADOWS, pixel)) return;  // the lighting pass reads no mask there
  uint rate = probe ? RB_RATE_FULL : itemRate(sel, RB_ITEM_SHADOWS);
  if (!rateTraces(rate, pixel)) return;  // the lighting pass fills it
  Surface s;
  if (!readSurfacePoint(pixel, objectId, s)) return;  // unlit
  uint start = clockNow();
  vec3 p, ng;
  readExactSurface(pixel, p, ng);
  vec3 origin = offsetRay(p, ng);
  bool classify = (frame.rayTracing.w & RB_RT_CLASSIFY_SHADOWS) != 0u;
  bool shorten = (frame.rayTracing.w & RB_RT_SHORTEN_SHADOW_RAYS) != 0u;
  bool reduced = rate != RB_RATE_FULL;
  uint work = 0u;
  bool traced = false;  // some light's ray was traced here
  rbPriorRays = priorRays(RB_ITEM_SHADOWS);
  // Lights the classifier finds certain need no ray.
  for (uint i = 0u; i < frame.sizeLightsFrame.z; ++i) {
    vec3 L;
    float dist, scale;
    float visible = 0.0, mapped = 0.0;
    if (lightSample(lights[i], p, L, dist, scale) && dot(s.normal, L) > 0.0) {
      if (classify && shadowMapCertain(lights[i], s.position, s.normal, ng, L, frame.exposure.y, mapped)) visible = mapped;
      else {
        if (reduced && !classify) mapped = shadowFromLight(lights[i], s.position, s.normal);
        visible = traceVisibility(origin, L, shorten ? shadowRayEnd(lights[i], origin, L, dist) : dist, work);
        traced = true;
      }
    }
    imageStore(shadowMask, ivec3(pixel, int(i)), vec4(visible));
    if (reduced) imageStore(shadowMask, ivec3(pixel, mappedLayer(i)), vec4(mapped));
  }
  if (traced && !probe) markTraced(pixel, RB_RT_SHADOWS);
  uint ticks = clockShare(start, clockNow(), subgroupAdd(1u));
  addObjectWork(s.objectId, probe ? 0u : work);  // (the per-object cost model learns from selected pixels)
  // The pixels a probe or a reduced rate traced are counted here (a full rate's at selection).
  bool counted = probe || reduced;
  if (measuringItems()) addItemCounts(s.objectId, uvec3(work, 0u, 0u), uvec3(ticks, 0u, 0u), uvec3(0u), uvec3(counted ? 1u : 0u, 0u, 0u));
}

// Past the deadline: where the pixel would have been traced (or probed), -1 in the light's
// first mask layer tells the lighting pass that the maps stand (shadowMaskWritten), and what
// the stage learns does without it (include/deadline_cut.glsl's leavePixel).
void leaveShadows(ivec2 pixel) {
  uint objectId = all(lessThan(uvec2(pixel), frame.sizeLightsFrame.xy)) ? texelFetch(gObjectId, pixel, 0).r : RB_NO_OBJECT;
  bool left = false, full = false;
  float work = 0.0;
  if (objectId != RB_NO_OBJECT) {
    Selection sel = selectionAt(objectId, pixel);
    uint rate = itemRate(sel, RB_ITEM_SHADOWS);
    bool selected = itemSelected(sel, RB_ITEM_SHADOWS);
    left = selected ? rateTraces(rate, pixel) : itemProbed(sel, RB_ITEM_SHADOWS, pixel);
    full = left && selected && rate == RB_RATE_FULL;
    if (left && selected) work = predictedPixelWork(objectId, RB_ITEM_SHADOWS, rate);
  }
  if (left) imageStore(shadowMask, ivec3(pixel, 0), vec4(-1.0));
  leavePixel(objectId, left, bvec3(full, false, false), work, true);
}

void main() {
  ivec2 pixel = chunkPixel(RB_SHADOW_CHUNKS);
  if (pastDeadline(false)) leaveShadows(pixel);
  else traceShadows(pixel);
  stampStageSpan();  // the shadow pass ends
}
