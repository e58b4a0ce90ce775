#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_ARB_shader_clock : require
#extension GL_EXT_shader_realtime_clock : require
#include "include/bindings.glsl"
#include "include/gbuffer.glsl"
#include "include/deadline_cut.glsl"
#include "include/probe.glsl"
#include "include/rates.glsl"
#include "include/tile_pixel.glsl"
#include "include/effect_fill.glsl"

// The fill of the reflections and refractions that reduced ray rates skipped this frame
// (include/effect_fill.glsl), over the chunks of the effect pass's tiles a reduced rate skips,
// in the ray-tracing stage. With RB_RT_MEASURE_ITEMS the filled pixels' time is charged to their
// items (their cost per pixel a reduced rate skips, GpuItemCost::fillPerPixel): the subgroup's
// span shared among the lanes that filled, each one's split over the paths it filled; in one
// workgroup of RB_FILL_MEASURE_STRIDE, turning with the frame. The cost per pixel is a ratio of
// ticks to pixels, which the sample estimates alike, and measuring every workgroup (two clock
// reads a lane and a subgroup's atomics per item) was a fifth of the pass (Suzanne, 1/16, a
// 30-frame orbit at 640x360 on lavapipe: 0.80 of its time without). The fill ran inside the effects pass
// before, from the tile's traced pixels in shared memory behind a barrier (which lavapipe runs
// as coroutines): as a pass of its own it costs about the same and reads across tiles
// (docs/SELECTION.md, "Ray rates"). The stage's deadline cuts it only at about T itself
// (include/stage_clock.glsl): a subgroup past it fills nothing and counts the pixels it leaves.
layout(local_size_x = RB_TRACE_GROUP_SIZE) in;

#define RB_FILL_MEASURE_STRIDE 4u

void main() {
  ivec2 pixel = chunkPixel(RB_FILL_CHUNKS);
  bool measured = measuringItems() && (gl_WorkGroupID.x + frame.sizeLightsFrame.w) % RB_FILL_MEASURE_STRIDE == 0u;
  uint start = measured ? clockNow() : 0u;
  uint objectId;
  bool past = fillPastDeadline(), left;
  bvec2 filled = fillEffects(pixel, past, objectId, left);
  if (past) {  // the whole subgroup
    countFillCut(left);
    return;
  }
  if (!measured) return;
  bool filling = any(filled);
  uint share = clockShare(start, clockNow(), subgroupAdd(filling ? 1u : 0u));
  uvec2 paths = uvec2(filled);
  uint each = share / max(paths.x + paths.y, 1u);
  addItemCounts(filling ? objectId : RB_NO_OBJECT, uvec3(0u), uvec3(0u), vec3(0.0), uvec3(0u), uvec3(0u, paths * each), uvec3(0u, paths));
}
