// What a trace pass does past the stage's deadline (include/stage_clock.glsl): whether a
// subgroup is past it, and what a pixel it leaves to its fallback takes off what the stage
// learns (TileListBlock::deadlineCut, the items' and the objects' counts).
// The includer enables GL_EXT_shader_realtime_clock, GL_ARB_shader_clock and
// GL_KHR_shader_subgroup_basic, _vote, _ballot and _arithmetic, and includes bindings.glsl.
#ifndef RB_DEADLINE_CUT_GLSL
#define RB_DEADLINE_CUT_GLSL
#include "include/item_stats.glsl"
#include "include/stage_clock.glsl"

// Whether the stage has run past `deadline` ticks, the same for the whole subgroup (one clock
// read each): `afterEffects` for the effects pass and the fill after it, whose time counts from
// the effects pass's start (the fallback and lighting passes before it are not the stage's),
// else the shadow pass.
bool stagePast(uint deadline, bool afterEffects) {
  if (deadline == 0u || stageClock.x == 0u) return false;
  uint since = subgroupBroadcastFirst(deviceClock()) - stageClock.x;
  uint began = stageClock.z;  // the effects pass's start (0: its workgroup 0 has not begun)
  uint spent = !afterEffects ? since : stageClock.y + (began == 0u ? 0u : since - (began - 1u));
  return spent > deadline;
}

// Whether a trace pass is past its deadline: `effects` for the effects pass, else the shadow pass.
bool pastDeadline(bool effects) { return stagePast(effects ? frame.stageDeadline.x : frame.stageDeadline.y, effects); }

// Whether the fill of reflections and refractions is past its deadline (about T itself): it is
// cut only where the stage would else end past T.
bool fillPastDeadline() { return stagePast(frame.stageDeadline.z, true); }

// The work the selection predicted for one pixel of item `effect` of the object traced at `rate`
// (0 where its cost was never learned, and for the object policies, which learn none per item).
float predictedPixelWork(uint objectId, uint effect, uint rate) {
  if (!measuringItems()) return 0.0;
  float perPixel = itemCosts[objectId * RB_ITEMS_PER_OBJECT + effect].workPerPixel;
  return rate == RB_RATE_FULL ? perPixel : perPixel * RB_TRACED_PIXEL_COST(rate);
}

// Counts this lane's `pixels` the deadline left to their fallbacks (the shadow pass's also on
// their own) and the `work` the selection predicted for them: one atomic each a subgroup.
void countCut(uint pixels, float work, bool shadows) {
  uint sum = subgroupAdd(pixels);
  float predicted = subgroupAdd(work);
  if (subgroupElect() && sum != 0u) {
    atomicAdd(deadlineCut.x, sum);
    atomicAdd(deadlineCut.y, uint(predicted * RB_CUT_WORK_UNITS + 0.5));
    if (shadows) atomicAdd(deadlineCut.z, sum);
  }
}

// Counts this lane's `left` pixels the fill left past its deadline: one atomic a subgroup.
void countFillCut(uint left) {
  uint sum = subgroupAdd(left);
  if (subgroupElect() && sum != 0u) atomicAdd(deadlineCut.w, sum);
}

// A pixel of `objectId` past the deadline (`left`: one its pass would have traced or probed):
// its object learns nothing this frame (the object policies count its pixels at selection), the
// items in `full`, whose full rate counted it at selection, take it off their count (a wrapping
// add) so that their cost and benefit are learned over the pixels traced, and the cut counts it
// with the `work` the selection predicted for it (`shadows`: the shadow pass's pixel).
void leavePixel(uint objectId, bool left, bvec3 full, float work, bool shadows) {
  if (left) objectCosts[objectId].pixels = 0u;
  countCut(left ? 1u : 0u, work, shadows);
  if (measuringItems()) addItemCounts(any(full) ? objectId : RB_NO_OBJECT, uvec3(0u), uvec3(0u), uvec3(0u), uvec3(full) * 0xFFFFFFFFu);
}

#endif
