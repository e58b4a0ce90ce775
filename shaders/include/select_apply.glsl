// Frame mode, after the walk has marked the selected objects (or items) in the frame's
// selection: object i's S for the next frame's relevance is set from it, and its traced
// pixel count noted; with `benefit` each item's S and traced pixels too, the candidate items
// the walk left out are marked for the probe when it runs, and the selected ones get their
// ray rate (shared/selection.h). select_apply.comp runs it per object; with few objects the
// walk runs it itself (select_walk.comp), a dispatch saved. The includer includes
// select_common.glsl.
#ifndef RB_SELECT_APPLY_GLSL
#define RB_SELECT_APPLY_GLSL

void applySelection(uint i) {
  uint bits = selected[i] & RB_ITEMS_ALL;
  float s = bits != 0u ? 1.0 : 0.0;
  if (s != params[i].kqiS.w) atomicAdd(result2.x, 1u);
  params[i].kqiS.w = s;
  // The pixels the trace passes will count work over, for next frame's learning.
  costs[i].pixels = bits != 0u ? floatBitsToUint(records[i].crCandidatePixels.w) : 0u;
  if (push.sizes.z != RB_SELECT_BENEFIT) return;
  bool probing = items[push.walk.z * RB_ITEMS_PER_OBJECT].pixels != 0u && records[i].crCandidatePixels.z > 0.5;
  // A fixed rate for every selected item, or each item's as the walk chose it.
  uint fixedRate = push.walk.w, marks = 0u, chosen = selected[i];
  for (uint effect = 0u; effect < RB_ITEMS_PER_OBJECT; ++effect) {
    uint id = i * RB_ITEMS_PER_OBJECT + effect;
    bool on = (bits & (1u << effect)) != 0u;
    uint pixels = itemPixels(i, effect);
    uint rate = fixedRate == RB_RATE_AUTO ? (chosen >> (RB_RATE_SHIFT + 2u * effect)) & 3u : fixedRate;
    // S, kept as the item's option: 0 left out, 1 + its rate (the flicker count compares them).
    uint option = on ? 1u + rate : 0u;
    if (items[id].selectedLast != option) atomicAdd(result3.x, 1u);
    items[id].selectedLast = option;
    // A probed item's, or one traced at a reduced rate: counted by the trace passes.
    items[id].pixels = on && rate == RB_RATE_FULL ? pixels : 0u;
    if (!on && probing && pixels > 0u) marks |= 1u << (RB_PROBE_SHIFT + effect);
    if (on && fixedRate != RB_RATE_AUTO) marks |= fixedRate << (RB_RATE_SHIFT + 2u * effect);
  }
  if (marks != 0u) selected[i] = chosen | marks;
}

#endif
