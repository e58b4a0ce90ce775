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
// (include/effect_fill.glsl), in the ray-tracing stage: one invocation per 4x4 block of each
// tile the tile list names (RB_FILL_CHUNKS: a tile's four blocks, one chunk), filling the block's
// skipped pixels one after the other, so that 1/16's lattice points around the block are read
// once (gatherLattice). With RB_RT_MEASURE_ITEMS the filled pixels' time is charged to their
// items (their cost per pixel a reduced rate skips, GpuItemCost::fillPerPixel): each pixel's
// span on the subgroup's clock, with those before it where no lane filled, shared among the
// paths the subgroup's lanes filled there; in one workgroup of RB_FILL_MEASURE_STRIDE, turning
// with the frame. The cost per pixel is a ratio of ticks to pixels, which the sample estimates
// alike, and measuring every workgroup was a fifth of the pass (an invocation per pixel then:
// Suzanne, 1/16, a 30-frame orbit at 640x360 on lavapipe). As a pass of its own (it ran inside the effects pass before, from the tile's traced
// pixels in shared memory behind a barrier, which lavapipe runs as coroutines) it reads across
// tiles (docs/SELECTION.md, "Ray rates"). The stage's deadline cuts it only at about T itself
// (include/stage_clock.glsl): a subgroup past it fills nothing and counts the pixels it leaves.
layout(local_size_x = RB_TRACE_GROUP_SIZE) in;

#define RB_FILL_MEASURE_STRIDE 4u

// What a lane's filled pixels of one object add to its items' fill counts (measured workgroups).
struct FillCharge {
  uint objectId;
  uvec2 ticks, pixels;  // per path
};

// Adds the lanes' charges whose object the next pixel leaves (`flush`), or all at the end, to
// their items: a subgroup's call, made where it is uniform.
void addCharge(inout FillCharge c, bool flush) {
  addItemCounts(flush ? c.objectId : RB_NO_OBJECT, uvec3(0u), uvec3(0u), uvec3(0u), uvec3(0u), uvec3(0u, c.ticks), uvec3(0u, c.pixels));
  if (flush) c = FillCharge(RB_NO_OBJECT, uvec2(0u), uvec2(0u));
}

void main() {
  uint g = gl_GlobalInvocationID.x, chunk = g / RB_TRACE_CHUNK;
  bool measured = measuringItems() && (gl_WorkGroupID.x + frame.sizeLightsFrame.w) % RB_FILL_MEASURE_STRIDE == 0u;
  bool past = fillPastDeadline();  // the whole subgroup
  bool listed = chunk < traceCounts.w;
  ivec2 origin = ivec2(0);
  if (listed) {
    origin = ivec2(chunkTile(tiles[RB_FILL_CHUNKS + chunk])) * RB_TILE_SIZE + ivec2(g & 1u, (g >> 1u) & 1u) * 4;
  }
  uint lastObject = RB_NO_OBJECT, left = 0u;
  Selection sel;
  FillCharge charge = FillCharge(RB_NO_OBJECT, uvec2(0u), uvec2(0u));
  uint start = measured && !past ? clockNow() : 0u;
  // The block's pixels by 1/16's lattice cells: the frame's lattice offset o splits the block
  // at o (the cells whose corners lie at origin + o - 4 and origin + o, each axis).
  ivec2 o = ivec2(sixteenthOffset(frame.sizeLightsFrame.w));
  for (int part = 0; part < 4; ++part) {
    ivec2 side = ivec2(part & 1, part >> 1);
    ivec2 lo = side * o, hi = mix(o, ivec2(4), bvec2(side));
    LatticeCell cell = latticeCell(origin + o - 4 + side * 4);
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        ivec2 pixel = origin + ivec2(x, y);
        bool inside = listed && all(lessThan(uvec2(pixel), frame.sizeLightsFrame.xy));
        uint objectId = inside ? texelFetch(gObjectId, pixel, 0).r : RB_NO_OBJECT;
        bvec2 filled = bvec2(false);
        if (objectId != RB_NO_OBJECT) {
          if (objectId != lastObject) {
            sel = selectionAt(objectId, pixel);  // one tile: the same for the block's pixels of the object
            lastObject = objectId;
          }
          bool leaves;
          filled = fillEffects(pixel, objectId, sel, past, cell, leaves);
          left += leaves ? 1u : 0u;
        }
        if (!measured || past) continue;
        uvec2 paths = uvec2(filled);
        uint sharing = subgroupAdd(paths.x + paths.y);
        if (sharing == 0u) continue;  // the span so far goes to the next pixel some lane fills
        uint now = clockNow(), each = clockShare(start, now, sharing);
        start = now;
        bool flush = any(filled) && charge.objectId != RB_NO_OBJECT && charge.objectId != objectId;
        if (subgroupAny(flush)) addCharge(charge, flush);
        if (any(filled)) {
          charge.objectId = objectId;
          charge.ticks += paths * each;
          charge.pixels += paths;
        }
      }
  }
  if (past) {
    countFillCut(left);
    return;
  }
  if (measured) addCharge(charge, charge.objectId != RB_NO_OBJECT);
}
