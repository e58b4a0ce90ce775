// Shared by the GPU selection shaders (shaders/select/select_*.comp): their own descriptor set
// (engine/src/select/gpu_selector.h) and push constants (shared/selection.h). The CPU reference is
// engine/src/select/policies.cpp; these shaders reproduce it exactly.
#ifndef RB_SELECT_COMMON_GLSL
#define RB_SELECT_COMMON_GLSL
#include "shared/random_rank.h"
#include "shared/selection.h"

layout(set = 0, binding = 0, std430) buffer CandidateBlock { GpuCandidate candidates[]; };
// Sort keys: the policy's key word, then the candidate's place in ID order (the tie-break,
// and where candidateAt finds the candidate).
layout(set = 0, binding = 1, std430) buffer OrderBlock { uvec2 order[]; };
layout(set = 0, binding = 2, std430) buffer RelevanceBlock { uvec2 relevance[]; };  // `paper`: the relevance order
layout(set = 0, binding = 3, std430) buffer ScratchBlock { uint scratch[]; };     // `paper`: per candidate, taken
layout(set = 0, binding = 4, std430) buffer FlagBlock { uint selectedFlags[]; };  // per candidate: 1 selected
// Frame mode: x candidates, y predicted cost and z value (float bits), w selected; then
// x objects whose selection changed since the last frame, y and z the candidates' total cost
// (allCandidatesFit), w 1 when the selection needed an order (FrameTiming::selectionSorted);
// then x `benefit`'s items whose option (left out, or a rate) changed since the last frame,
// y the predicted cost of the selected candidates priced by the prior (float bits;
// select_walk.comp's priorPricedCost); then the candidate pass's largest x cost and y value
// (float bits), the walk's scales for its sums in no order.
layout(set = 0, binding = 5, std430) buffer ResultBlock { uvec4 result; uvec4 result2; uvec4 result3; uvec4 result4; };
// Frame mode: the renderer's per-object records, selection and K/Q/I/S (shared/selection.h).
layout(set = 0, binding = 6, std430) readonly buffer RecordBlock { GpuObjectRecord records[]; };
layout(set = 0, binding = 7, std430) buffer SelectedBlock { uint selected[]; };
layout(set = 0, binding = 8, std430) buffer ParamsBlock { GpuObjectParams params[]; };
layout(set = 0, binding = 9, std430) buffer CostBlock { GpuObjectCost costs[]; };
// Frame mode: per object, its candidate slot (select_candidates.comp appends candidates in
// any order; the keys carry object IDs).
layout(set = 0, binding = 11, std430) buffer SlotBlock { uint slotOf[]; };
// The greedy policies' order as the walk reads it (select_gather.comp): per position the
// candidate's cost and value (float bits), slot and ID.
layout(set = 0, binding = 13, std430) buffer WalkOrderBlock { uvec4 walkOrder[]; };
// Frame mode, `benefit`: the coverage pass's per-object counts (the classifier's pixels per
// effect) and what each item learned (shared/selection.h).
layout(set = 0, binding = 14, std430) readonly buffer CoverageBlock { GpuCoverage coverage[]; };
layout(set = 0, binding = 15, std430) buffer ItemBlock { GpuItemCost items[]; };

layout(push_constant) uniform SelectPushBlock { SelectPush push; };

// Candidates: given (push) or, in frame mode, counted on the GPU by select_candidates.comp.
uint candidateCount() { return push.walk.y != 0u ? result.x : push.sizes.x; }

// Frame mode: whether every candidate fits the budget for certain, so that every policy
// selects them all and no order is needed (the sorts exit, the walk marks them all). The
// candidate pass sums their costs in units of 2^-20 budget rounded up (exact integers);
// "certain" leaves 1/32 of the budget for float rounding: the walks subtract in float, each
// subtraction off by at most 2^-24 budget, so after n <= 2^18 steps what remains is still
// above the next cost. Then greedy takes all (and density's best single cannot beat the sum
// of all values, partial float sums of values >= 0 never decrease), and the paper's walk
// finds a fitting node until every node is taken.
bool allCandidatesFit() { return push.walk.y != 0u && result.x <= RB_ALL_FIT_MAX_CANDIDATES && result2.z == 0u && result2.y <= RB_ALL_FIT_UNITS; }

// The part of the key array the sort must order: the candidates rounded up to a power of
// two (at least one 1024-key block). In frame mode the dispatches cover every object; the
// invocations beyond this size (usually most: only visible objects are candidates) exit.
uint sortSize() {
  uint n = max(candidateCount(), 1u);
  uint p = n == 1u ? 1u : 1u << uint(findMSB(n - 1u) + 1);
  return min(max(p, 1024u), push.sizes.y);
}


// Float bits mapped so that unsigned order is float order (ascending).
uint orderedBits(float f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}

bool keyLess(uvec2 a, uvec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; }

// The candidate of a key's second word: in frame mode an object ID; for select() the slot,
// the host having uploaded the candidates in ID order.
uint candidateAt(uint word) { return push.walk.y != 0u ? slotOf[word] : word; }

// The walk's record of candidate slot ci in a greedy policy's order (select_gather.comp):
// cost, value, slot, ID.
uvec4 greedyRecord(uint ci) {
  GpuCandidate c = candidates[ci];
  return uvec4(floatBitsToUint(c.cost), floatBitsToUint(c.value), ci, c.id);
}

// The sort key of candidate i for the policy's order (which = 0) or `paper`'s relevance
// order (1): ascending = selection order. The policy's word, then the candidate's place in
// ID order, so keys are unique, ties go by ID, and a key is 8 bytes (a merge sort on a CPU
// device moves it scattered, lane by lane: 16-byte keys cost ~1.5x as much). Past the
// candidates: all ones, sorted last.
// a / b correctly rounded, as the CPU reference divides. Vulkan lets a float division be
// 2.5 ULP off (NVIDIA's is; lavapipe's is exact), which reordered near-equal densities
// against the CPU on an H100. A double quotient within 2.5 double ULP of a / b rounds to the
// correctly rounded float: a quotient of two floats is never within 2^-49 (relative) of a
// midpoint between floats, and 2.5 double ULP is under 2^-51.
float exactQuotient(float a, float b) { return float(double(a) / double(b)); }

// `benefit`: the pixels item `effect` of object i covers this frame (0: nothing to trace):
// shadows every pixel of the object (the shadow pass classifies per light), reflections and
// refractions the classifier's counts; none for an effect the frame does not trace or a
// scene without lights. cost_model.cpp's itemPixels is the CPU reference.
// The share of an item's full-rate cost a ray rate costs, a pixel it skips costing `fill` of a
// traced pixel's full-rate cost (shared/selection.h; cost_model.cpp's rateShare). Precise: a
// fused multiply-add would round otherwise than the CPU.
float rateShare(uint rate, float fill) {
  if (rate != RB_RATE_HALF && rate != RB_RATE_QUARTER && rate != RB_RATE_SIXTEENTH) return 1.0;
  precise float skipped = (rate == RB_RATE_HALF ? 0.5 : (rate == RB_RATE_QUARTER ? 0.75 : 0.9375)) * fill;
  precise float share = (rate == RB_RATE_HALF ? RB_TRACED_SHARE_HALF : (rate == RB_RATE_QUARTER ? RB_TRACED_SHARE_QUARTER : RB_TRACED_SHARE_SIXTEENTH)) + skipped;
  return share;
}

// An item's fill share: its learned cost per skipped pixel over its cost per pixel at full rate,
// at most RB_FILL_SHARE_MAX; the effect's prior before either was learned (cost_model.cpp's fillShare).
float fillShare(uint effect, float fillPerPixel, float workPerPixel) {
  if (fillPerPixel > 0.0 && workPerPixel > 0.0) return min(exactQuotient(fillPerPixel, workPerPixel), RB_FILL_SHARE_MAX);
  return effect == RB_ITEM_SHADOWS ? RB_FILL_SHARE_PRIOR_SHADOWS : RB_FILL_SHARE_PRIOR;
}

// The clock time of a pixel a rate traces over full rate's per pixel (shared/selection.h;
// cost_model.cpp's tracedPixelCost).
float tracedPixelCost(uint rate) { return RB_TRACED_PIXEL_COST(rate); }

// The quality of an item's fill at 1/16 (x) and at 1/4 (y) this frame: the effect's prior, or
// toward RB_FILL_QUALITY_STILL on a still view (shared/selection.h; cost_model.cpp's
// frameFillQualities fills the push constants).
vec2 fillQualities(uint effect) { return vec2(push.sixteenthQuality[effect], push.quarterQuality[effect]); }

// The share of object i's reflection and refraction pixels whose neighbours' normals agree
// (shared/selection.h's RB_FILL_DETAIL_COS; cost_model.cpp's fillSmoothness).
float fillSmoothness(uint i) {
  uvec4 c = coverage[i].sumYHi;
  uint pixels = max(c.y, c.z);
  return pixels == 0u ? 1.0 : exactQuotient(float(pixels - min(c.w, pixels)), float(pixels));
}

// Item (object i, effect)'s fill qualities at 1/16 (x) and 1/4 (y): a shadow item's are the
// frame's; a reflection or refraction item's spatial priors are scaled by its object's
// smoothness g (g and g^2) before the still view's move toward RB_FILL_QUALITY_STILL (with
// g = 1 the frame's, bit for bit; cost_model.cpp's itemFillQuality).
vec2 itemFillQualities(uint i, uint effect) {
  if (effect == RB_ITEM_SHADOWS) return fillQualities(effect);
  bool reflections = effect == RB_ITEM_REFLECTIONS;
  float g = fillSmoothness(i);
  precise float g2 = g * g;
  precise float quarter = (reflections ? RB_FILL_QUALITY_QUARTER_REFLECTIONS : RB_FILL_QUALITY_QUARTER_REFRACTIONS) * g;
  precise float sixteenth = (reflections ? RB_FILL_QUALITY_SIXTEENTH_REFLECTIONS : RB_FILL_QUALITY_SIXTEENTH_REFRACTIONS) * g2;
  precise float q4 = quarter + (RB_FILL_QUALITY_STILL - quarter) * push.quarterQuality.w;
  precise float q16 = sixteenth + (RB_FILL_QUALITY_STILL - sixteenth) * push.sixteenthQuality.w;
  return vec2(q16, q4);
}

// The share of an item's full-rate value that `rate` keeps at fill qualities q (fillQualities):
// its traced pixels' and the filled ones' (cost_model.cpp's keepShare).
float keepShare(uint rate, vec2 q) {
  if (rate != RB_RATE_QUARTER && rate != RB_RATE_SIXTEENTH) return 1.0;
  precise float filled = (rate == RB_RATE_QUARTER ? 0.75 * q.y : 0.9375 * q.x);
  precise float keep = (rate == RB_RATE_QUARTER ? 0.25 : 0.0625) + filled;
  return keep;
}

// Whether option b lies strictly above the line from a to c in (cost, value), costs in order.
bool aboveChord(vec2 a, vec2 b, vec2 c) {
  precise float rise = (b.y - a.y) * (c.x - a.x);
  precise float chord = (c.y - a.y) * (b.x - a.x);
  return rise > chord;
}

// The reduced rates on the upper convex hull of an item's options skip, 1/16, 1/4, full in
// (cost share, value share) at fill share `fill` and the item's fill qualities q (itemFillQualities)
// (RB_HULL_* bits): a rate below the line between its neighbours on the hull is
// left out (Funkhouser and Sequin's dominated option), so that the segments' value per cost
// falls (cost_model.cpp's rateHull).
uint rateHull(vec2 q, float fill) {
  vec2 skip = vec2(0.0), full = vec2(1.0);
  vec2 sixteenth = vec2(rateShare(RB_RATE_SIXTEENTH, fill), keepShare(RB_RATE_SIXTEENTH, q));
  vec2 quarter = vec2(rateShare(RB_RATE_QUARTER, fill), keepShare(RB_RATE_QUARTER, q));
  bool onSixteenth = aboveChord(skip, sixteenth, quarter);
  bool onQuarter = aboveChord(onSixteenth ? sixteenth : skip, quarter, full);
  if (!onQuarter && onSixteenth) onSixteenth = aboveChord(skip, sixteenth, full);
  return (onSixteenth ? RB_HULL_SIXTEENTH : 0u) | (onQuarter ? RB_HULL_QUARTER : 0u);
}

// RB_RATE_AUTO's segments of an item with the rates `hull` (rateHull): how many, the
// rate segment k reaches, and its shares of the item's full-rate value (at fill qualities q)
// and cost (at fill share `fill`) (cost_model.cpp's rateSegment is the CPU reference).
uint rateSegments(uint hull) { return 1u + bitCount(hull); }
uint segmentRate(uint k, uint hull) {
  uint step = k;
  if ((hull & RB_HULL_SIXTEENTH) != 0u) {
    if (step == 0u) return RB_RATE_SIXTEENTH;
    --step;
  }
  if ((hull & RB_HULL_QUARTER) != 0u && step == 0u) return RB_RATE_QUARTER;
  return RB_RATE_FULL;
}
float segmentValueShare(uint k, uint hull, vec2 q) {
  precise float gain = keepShare(segmentRate(k, hull), q) - (k == 0u ? 0.0 : keepShare(segmentRate(k - 1u, hull), q));
  return gain;
}
float segmentCostShare(uint k, float fill, uint hull) {
  precise float cost = rateShare(segmentRate(k, hull), fill) - (k == 0u ? 0.0 : rateShare(segmentRate(k - 1u, hull), fill));
  return cost;
}
// The rates on item `item`'s hull this frame, from what the candidate pass learned (the walk
// reads it back to mark levels).
uint itemHull(uint item) {
  GpuItemCost c = items[item];
  uint effect = item % RB_ITEMS_PER_OBJECT;
  return rateHull(itemFillQualities(item / RB_ITEMS_PER_OBJECT, effect), fillShare(effect, c.fillPerPixel, c.workPerPixel));
}

// Whether the walk selects rate segments (`benefit` with RB_RATE_AUTO), and a candidate's item.
bool rateSegmentsWalk() { return push.sizes.z == RB_SELECT_BENEFIT && push.walk.w == RB_RATE_AUTO; }
uint candidateItem(uint id) { return rateSegmentsWalk() ? id / RB_SEGMENT_SLOTS : id; }

uint itemPixels(uint i, uint effect) {
  if ((push.items.x & (1u << effect)) == 0u) return 0u;
  if (effect == RB_ITEM_SHADOWS) return push.items.y > 0u ? floatBitsToUint(records[i].crCandidatePixels.w) : 0u;
  return effect == RB_ITEM_REFLECTIONS ? coverage[i].sumYHi.y : coverage[i].sumYHi.z;
}

// The frame's selection: marks candidate `id` selected (an object: all its items; an item of
// `benefit`: its bit, lanes may mark items of one object at once), or clears its object.
void markSelected(uint id) {
  if (push.sizes.z == RB_SELECT_BENEFIT) atomicOr(selected[id / RB_ITEMS_PER_OBJECT], 1u << (id % RB_ITEMS_PER_OBJECT));
  else selected[id] = RB_ITEMS_ALL;
}
void clearSelected(uint id) { selected[push.sizes.z == RB_SELECT_BENEFIT ? id / RB_ITEMS_PER_OBJECT : id] = 0u; }
// Whether the frame's selection marks `benefit`'s item `item` (an object's RB_ITEMS_PER_OBJECT bits).
bool itemMarked(uint item) { return (selected[item / RB_ITEMS_PER_OBJECT] & (1u << (item % RB_ITEMS_PER_OBJECT))) != 0u; }

uvec2 candidateKey(uint i, uint which) {
  if (i >= candidateCount()) return uvec2(0xFFFFFFFFu);
  GpuCandidate c = candidates[i];
  uint place = push.walk.y != 0u ? c.id : i, policy = push.sizes.z;
  if (policy == RB_SELECT_DENSITY || policy == RB_SELECT_BENEFIT) {
    float density = c.cost > 0.0 ? exactQuotient(c.value, c.cost) : uintBitsToFloat(0x7F800000u);
    return uvec2(~orderedBits(density), place);
  }
  if (policy == RB_SELECT_NEAREST) return uvec2(orderedBits(c.distance), place);
  if (policy == RB_SELECT_RANDOM) return uvec2(randomRank(push.sizes.w, c.id), place);
  if (which == 0u) return uvec2(~orderedBits(c.cost), place);  // `paper`: the cost chain, most costly first
  return uvec2(~orderedBits(c.value), place);                  // `paper`: the relevance order, most relevant first
}

#endif
