// GPU records of the heuristic's per-object pass (shaders/select/coverage.comp and
// shaders/select/object_metrics.comp), shared by C++ and GLSL. The arithmetic matches
// engine/src/select/metrics.cpp.
#ifndef RAYBUDGET_SHARED_SELECTION_H
#define RAYBUDGET_SHARED_SELECTION_H

#ifdef __cplusplus
#include "shared/types.h"
namespace raybudget::gpu {
#endif

// 32 bytes: an object's pixels in the object-ID buffer and the 64-bit sums of their integer
// coordinates, as lo/hi 32-bit words (portable: no 64-bit atomics needed), and the pixels
// the classifier marked for reflection and refraction rays.
struct GpuCoverage {
  uvec4 pixelsSumX;  // x pixels, y sum x lo, z sum x hi, w sum y lo
  uvec4 sumYHi;      // x sum y hi, y reflection pixels, z refraction pixels, w of those the detailed ones (RB_FILL_DETAIL_COS)
};

// 32 bytes: the object's authored or derived K, Q, I, and w = 1 when it was selected last
// frame (S); and its items' prior benefit per covered pixel (x shadows, y reflections,
// z refractions), from its materials (engine/src/select/object_params.h).
struct GpuObjectParams {
  vec4 kqiS;
  vec4 priors;
};

// 32 bytes: A, P, D, V and C, R, candidate (1/0), pixels (uint bits).
struct GpuObjectRecord {
  vec4 apdv;
  vec4 crCandidatePixels;
};

// 16 bytes: what the cost model knows of an object: its learned traversal work per traced
// pixel (0: not learned yet, Q times a prior is used), and the work the trace passes counted
// for it this frame over the pixels it was traced on.
struct GpuObjectCost {
  float workPerPixel;
  uint work;
  uint pixels;
  uint unused;
};

// Traversal work (BVH nodes + triangles) per ray at the prior time scale: the work a ray
// costs before any frame was timed (cost_model.h's TimeScale::priorWorkPerRay).
#define RB_PRIOR_WORK_PER_RAY 32.0

// Items: each object offers one per effect, item = object * RB_ITEMS_PER_OBJECT + effect. The
// frame's selection holds per object the bits of its selected items (1 << effect, the
// RB_RT_* bits of shared/config.h): the per-object policies select all three or none.
#define RB_ITEMS_PER_OBJECT 3u
#define RB_ITEM_SHADOWS 0u
#define RB_ITEM_REFLECTIONS 1u
#define RB_ITEM_REFRACTIONS 2u
#define RB_ITEMS_ALL 7u
// The rays an item's prior prices per pixel (TimeScale::priorWorkPerRay), and the trace passes
// count at each pixel they trace for it: a shadow ray per light; a reflection or refraction
// path (a refraction enters and leaves: 2) and the shadow rays of its hit.
#define RB_ITEM_PRIOR_RAYS(lights, effect) ((lights) + (effect))

// The trace passes' error sums (GpuItemCost::error): per traced pixel, the mean absolute
// difference of the display-space (tonemapped, sRGB-encoded) channels between the traced
// result and the fallback, in units of 1/RB_ERROR_UNITS (a 2^32 sum holds 4M pixels at 1).
#define RB_ERROR_UNITS 1024.0
// An item's benefit per covered pixel before it was measured, and where an untraced item's
// estimate drifts to (by RB_BENEFIT_DRIFT of the gap per frame, a power of two so that the
// step is exact and the CPU reference equals it): optimistic, so that an unmeasured or
// long-untraced item gets traced and measured again (docs/SELECTION.md). Per effect, for a
// perfect mirror and clear glass; an object's materials scale them (GpuObjectParams::priors).
#define RB_PRIOR_BENEFIT_SHADOWS 0.005
#define RB_PRIOR_BENEFIT_REFLECTIONS 0.15
#define RB_PRIOR_BENEFIT_REFRACTIONS 0.15
#define RB_BENEFIT_DRIFT 0.0625
// `benefit`'s ablations (SelectPush::items.w): P = 1 in E; I = 0; b the prior, never learned.
#define RB_BENEFIT_WITHOUT_CENTRALITY 1u
#define RB_BENEFIT_WITHOUT_HYSTERESIS 2u
#define RB_BENEFIT_PRIOR_ONLY 4u
// Items learn their cost from traversal work, not clock ticks: with the time scale held at its
// prior (RenderSettings::learnTimeScale off), whose unit is traversal work, so that selections
// depend on nothing timed (the editor's --fixed-time-scale, the sweep's --prior-time-scale).
#define RB_ITEM_COSTS_UNTIMED 8u

// The sparse probe (`benefit`): candidate items the walk left out are traced, measured and
// not shown, on the 8x8 tiles whose turn it is this frame, one tile in `stride` each frame in
// rotation (shaders/include/probe.glsl), with `stride` the least that keeps the probe's
// predicted cost within its share of the budget. The frame's selection holds a probed item's
// bit at RB_PROBE_SHIFT + effect; more than RB_PROBE_MAX_STRIDE needed: no probe that frame
// (at 1/256, the most before, a budget under about a twentieth of what was left out, priced
// from the prior, never probed and so never learned its items' costs).
#define RB_PROBE_SHIFT 3u
#define RB_PROBE_MAX_STRIDE 1024u
// A probe's observed work per pixel moves an item's estimate by half from this many pixels
// probed, by a quarter from a quarter of them, else by an eighth (cost_model.h's learnItem).
#define RB_PROBE_TRUSTED_PIXELS 512u

// Ray rates: the share of a selected item's pixels traced this frame: all, a checkerboard (1/2),
// one pixel of each 2x2 quad (1/4) or of each 4x4 block (1/16), rotating over frames (shaders/include/rates.glsl); the
// others are filled from traced neighbours on the same object (shaders/include/fill_weights.glsl). The
// frame's selection holds an item's rate in 2 bits at RB_RATE_SHIFT + 2 * effect (0: full).
#define RB_RATE_SHIFT 6u
#define RB_RATE_FULL 0u
#define RB_RATE_HALF 1u
#define RB_RATE_QUARTER 2u
#define RB_RATE_SIXTEENTH 3u
// `benefit` chooses each item's rate (SelectPush::walk.w): the multiple-choice knapsack over
// the items' rate options, greedy on each item's upper convex hull of (cost, value), one
// candidate per hull segment: candidate ID item * RB_SEGMENT_SLOTS + k for segment k, which
// may be taken only after segment k - 1 (docs/SELECTION.md).
#define RB_RATE_AUTO 4u  // (a push constant's value beside the rate codes, not a code)
#define RB_SEGMENT_SLOTS 4u
// The share of an item's full-rate benefit a rate keeps: its own traced pixels, plus what the fill
// keeps of the benefit at the pixels it skips, its quality q (1: as if traced, 0: the fallback's):
//   keep(1/4) = 0.25 + 0.75 q(1/4),  keep(1/16) = 0.0625 + 0.9375 q(1/16).
// q is a prior per effect: the display difference from full rate against the fallback's (mean
// over the image, tests/rates_test.cpp's metric), the effect alone traced, the median over the
// court and the plaza from their default camera and 30 degrees either way around, 480x270, with
// a fill inside the tile: reflections kept 0.78 at 1/4 and 0.60 at 1/16, refractions 0.90 and
// 0.78, q(1/4) 0.7067 and 0.8667, q(1/16) 0.5733 and 0.7653 (literals: glslang folds constant
// arithmetic in double, C++ in float, and the two must round alike). The fill reading across
// tiles (include/fill_weights.glsl) keeps 0.01-0.04 more at 1/4 and 0.03-0.08 more at 1/16 on
// FLIP (bench/rate_keep.py); the priors stay the older, lower figures. Learned per item from
// a leave-one-out prediction at the traced pixels, q recovered less on the benchmark (0.303 of
// the error at 25% of full RT's cost against 0.477 with the priors, docs/BENCHMARKS.md) and
// was dropped.
// Shadows, their fill correcting the shadow map in the lighting pass (include/shadow_fill.glsl),
// keep less: their error lies in lines a pixel wide along the maps' shadow edges, which a
// sparser lattice of traced pixels samples poorly. Measured the same way (`all`, shadows alone,
// bench/rate_keep.py on the court, the plaza, CesiumMilkTruck and SheenChair, 12 views): keep
// 0.40 at 1/4 and 0.10 at 1/16 (median), q(1/4) 0.2027 and q(1/16) 0.0368.
#define RB_FILL_QUALITY_QUARTER_REFLECTIONS 0.7067
#define RB_FILL_QUALITY_QUARTER_REFRACTIONS 0.8667
#define RB_FILL_QUALITY_SIXTEENTH_REFLECTIONS 0.5733
#define RB_FILL_QUALITY_SIXTEENTH_REFRACTIONS 0.7653
#define RB_FILL_QUALITY_QUARTER_SHADOWS 0.2027
#define RB_FILL_QUALITY_SIXTEENTH_SHADOWS 0.0368
// On a still view (the camera and every object where they were the frame before) the temporal
// fills (include/fill_history.glsl, shadow_history.glsl) carry each skipped pixel's traced
// change until its rate traces it again, so a rate keeps nearly what full rate shows once
// every pixel of its pattern was traced since the view stopped: measured like the priors
// after 20 still frames (bench/rate_keep.py --views static:20, every effect, 480x270, the
// court, the plaza and six bench scenes), keep 0.971-0.996 at 1/4 and 0.947-0.996 at 1/16,
// medians 0.986 and 0.979, q 0.98 at both. The frame's q moves from the prior toward
// RB_FILL_QUALITY_STILL by the share of the pattern's skipped pixels the still frames before
// it traced, min(1, n / (period - 1)) after n of them (exact for an item traced at that rate
// all along; cost_model.cpp's frameFillQualities): after a camera jump or on a moving view
// the prior stands. Shadows beyond RB_SHADOW_HISTORY_LIGHTS lights keep the prior.
#define RB_FILL_QUALITY_STILL 0.98
// Detail defeats the spatial fill: where the normals of neighbouring pixels differ (a small
// curved mirror, a normal map's bumps), what tracing changes differs between them too, and the
// fill, weighting neighbours by normal agreement and shrinking a mean they disagree on, keeps
// the fallback (bench/rate_keep.py: a normal-mapped mirror's 1/16 keeps -0.14-0.22 of its gap,
// MetalRoughSpheres' small spheres 0.02-0.07; the priors, from the court and the plaza, keep
// 0.60 at 1/16 and 0.78 at 1/4). The coverage pass counts, per object, the pixels needing
// reflection or refraction rays in a 2x2 quad where two pixels of the object have normals
// further apart than this cosine (GpuCoverage::sumYHi.w); the share of
// the others, g, scales a reflection or refraction item's spatial quality: g q(1/4) and g^2
// q(1/16) (1/16's neighbours lie four pixels apart), before the still view's move toward
// RB_FILL_QUALITY_STILL, which the temporal fill keeps whatever the detail
// (select_common.glsl's itemFillQualities, cost_model.cpp's itemFillQuality).
#define RB_FILL_DETAIL_COS 0.995
// The share of an item's full-rate cost a rate costs is not the share of its rays: every pixel
// of the item is still read, and the skipped ones are filled (fill_effects.comp: they read their
// surface and their neighbours', and with the temporal fill reproject and write their history).
// Measured on `all` at 640x360 on lavapipe, the effects pass with its fill then inside it at 1/2,
// 1/4 and 1/16 over full on 12-frame orbits with the temporal fill (the mean of two runs), the shares run from TransmissionTest's 0.63, 0.34, 0.15
// to the WaterBottle's 1.10, 0.77, 0.50 (the court 0.69, 0.41, 0.21; Suzanne 0.85, 0.57, 0.34),
// a spread no constant prices. So each item learns it: a pixel its rate traces costs
// RB_TRACED_PIXEL_COST_* times its full-rate cost per pixel (its clock ticks over its traced
// pixels, below), and a pixel its rate skips costs fill = GpuItemCost::fillPerPixel, learned from
// the skipped pixels' ticks. As a share of full rate, with f = fill / workPerPixel (clamped to
// [0, RB_FILL_SHARE_MAX]; RB_FILL_SHARE_PRIOR before a skipped pixel was timed):
//   share(1/2) = 0.5 * 1.3 + 0.5 f,  share(1/4) = 0.25 * 1.33 + 0.75 f,  share(1/16) = 0.0625 * 1.65 + 0.9375 f
// (RB_TRACED_SHARE_* are the first terms; cost_model.cpp's rateShare is the CPU reference). On
// `classified` the items' ticks at 1/4 and 1/16 over full follow the pass's time (the WaterBottle
// 0.69 and 0.45 against 0.84 and 0.55 ms, TransmissionTest 0.33, 0.14 against 0.34, 0.16).
// A pixel a reduced rate traces costs more clock time than one of full rate (its neighbours'
// rays and gathers do not run beside it; 1/16's lie four pixels apart): per traced pixel over
// full rate's per pixel, `classified` at 640x360 on lavapipe, the median over the items of the
// court (14) and the plaza (51-53): 1.29 and 1.33 at 1/2, 1.33 and 1.33 at 1/4 (Suzanne's 1.31).
// At 1/16 the median over all their traced items (58 and 170, 16 still frames each): 1.65 and
// 1.64 (Suzanne 1.70), since the trace passes run chunks of 4 pixels (tile_pixel.glsl), so two
// tiles' 1/16 pixels share a SIMD batch; 2.29 and 2.24 when each tile had a workgroup and its four
// pixels half a batch. An item learns its cost per pixel
// at full rate from its traced pixels' ticks divided by its rate's factor, so that
// its rates are priced from the same figure whatever rate measured it.
#define RB_TRACED_PIXEL_COST_HALF 1.3
#define RB_TRACED_PIXEL_COST_QUARTER 1.33
#define RB_TRACED_PIXEL_COST_SIXTEENTH 1.65
// The frames after which a rate traces a pixel again (rates.glsl's patterns).
#define RB_RATE_PERIOD(rate) ((rate) == RB_RATE_HALF ? 2u : (rate) == RB_RATE_QUARTER ? 4u : (rate) == RB_RATE_SIXTEENTH ? 16u : 1u)
// Per rate (RB_RATE_*), 1 at full rate.
#define RB_TRACED_PIXEL_COST(rate)                                                                                           \
  ((rate) == RB_RATE_HALF ? RB_TRACED_PIXEL_COST_HALF                                                                         \
                          : (rate) == RB_RATE_QUARTER ? RB_TRACED_PIXEL_COST_QUARTER                                          \
                                                      : (rate) == RB_RATE_SIXTEENTH ? RB_TRACED_PIXEL_COST_SIXTEENTH : 1.0)
#define RB_TRACED_SHARE_HALF 0.65        // 0.5 * RB_TRACED_PIXEL_COST_HALF (literals, as RB_FILL_QUALITY_*)
#define RB_TRACED_SHARE_QUARTER 0.3325   // 0.25 * RB_TRACED_PIXEL_COST_QUARTER
#define RB_TRACED_SHARE_SIXTEENTH 0.103125  // 0.0625 * RB_TRACED_PIXEL_COST_SIXTEENTH
// The prior fill share: the skipped pixels' ticks of the court, Suzanne, the WaterBottle and
// TransmissionTest at 1/4 and 1/16 gave 0.0-0.48, the court 0.01-0.03, Suzanne 0.16-0.17 (with
// an invocation per skipped pixel; the fill's invocation per 4x4 block costs about 0.6-0.8 of it).
// Shadows fill in the lighting pass, outside the stage: a skipped pixel costs the shadow pass
// its object's read alone, which is not timed. Their share is the pass's: `classified` on
// CesiumMilkTruck's fly-through (640x360, the cheapest rays of the bench scenes) cost 0.37 of
// full rate at 1/4 and 0.24 at 1/16, a fill share of 0.045 and 0.105.
#define RB_FILL_SHARE_PRIOR 0.125
#define RB_FILL_SHARE_PRIOR_SHADOWS 0.0625
// A fill share above this is priced at it (the dearest measured, the WaterBottle's, is about
// 0.3-0.5): below it 1/16 costs less than 1/4 and 1/4 less than full, so the options stay in order.
#define RB_FILL_SHARE_MAX 0.59
// Each item offers its options 1/16, 1/4 and full as the segments of their upper convex hull in
// (cost, value) from skipping (Funkhouser and Sequin's dominated options left out): skip -> 1/16 ->
// 1/4 -> full, costing share(1/16), share(1/4) - share(1/16) and 1 - share(1/4) of its full-rate
// cost for keep(1/16), keep(1/4) - keep(1/16) and 1 - keep(1/4) of its value. A rate below the
// line between its neighbours on the hull is left out (select_common.glsl's rateHull): at the
// prior shares and qualities the value per cost is 2.3, 1.07 and 0.38 for reflections, 3.0, 0.71
// and 0.17 for refractions, all three; from a fill share of 0.32 (reflections) or 0.52
// (refractions) 1/16 falls below the line from skipping to 1/4; a fill that keeps little (q near
// 0) leaves full rate alone, a temporal fill of a still view that keeps all (q near 1) 1/16
// alone. 1/2 lies near the line from 1/4 to full (at the constant shares measured before:
// within 0.01 of value) and is left out.
#define RB_HULL_SIXTEENTH 1u  // rateHull's bits: 1/16 and 1/4 on the hull
#define RB_HULL_QUARTER 2u

// `benefit` with rates chosen per item, frame mode: where the walk leaves budget over, the first
// item in its order whose first segment (1/16 for reflections and refractions) did not fit is
// traced on a share of its 8x8 tiles, the budget left over its cost, when that share is at
// least RB_PARTIAL_MIN_SHARE: the tiles whose hash (probe.glsl's tileTurn) falls below the share,
// the same tiles every frame. The items' totals record holds it (GpuItemCost).
#define RB_NO_PARTIAL 0xFFFFFFFFu
#define RB_PARTIAL_MIN_SHARE 0.125

// 44 bytes: what the `benefit` policy knows of an item: its learned cost per traced pixel in
// work units (0: not learned), the traversal work, time (subgroup clock ticks /
// RB_CLOCK_UNIT) and error the trace passes counted for it this frame over `pixels` (the
// pixels it was traced on), its learned benefit b (display error removed per covered pixel),
// 1 once measured, S as last frame's option (0: left out; 1 + its rate), and its learned cost
// per pixel its rate skips with this frame's ticks and count of such pixels. One more record
// after the items holds, in `pixels`, the frame's probe stride (0: no probe), in `selectedLast` the partial item + 1 (0:
// none) and in `benefit` its share of tiles. A probed item's `pixels` start at 0
// and count the covered pixels the probe traced.
struct GpuItemCost {
  float workPerPixel;
  uint work;
  uint pixels;
  uint error;
  float benefit;
  uint measured;
  uint selectedLast;
  uint ticks;
  float fillPerPixel;  // learned work units per pixel its reduced rate skips (0: not learned)
  uint skippedTicks;   // this frame's ticks (RB_CLOCK_UNIT) of the pixels its rate skipped
  uint skippedPixels;  // and how many
};
// Units per item work unit of the work the selection predicted for the pixels the stage's
// deadline left out (TileListBlock::deadlineCut.y, include/stage_clock.glsl).
#define RB_CUT_WORK_UNITS 16.0
// Clock ticks per unit of GpuItemCost::ticks: a 32-bit sum then holds 2^36 ticks a frame.
#define RB_CLOCK_UNIT 16u
// Item work units per RB_CLOCK_UNIT ticks: an item's cost is its traced pixels' time, and the
// time scale (ms per unit) is learned from the timestamps. A fixed rate, not one measured per
// frame (all items' traversal work over all their ticks), which followed the view: on
// ClearCoatTest's orbit from one camera to the next the reflection items' traversal work per
// pixel fell tenfold (43 nodes to 2-5: their rays left for the sky) while their ticks per pixel
// halved, so every item's learned cost fell about fivefold in units whose milliseconds the time
// scale learns two frames late. 0.5 (exact in float) puts lavapipe's item costs near the
// traversal work counts of the object policies' unit.
#define RB_WORK_PER_CLOCK_UNIT 0.5

// Frame mode: the candidates' total cost in units of 2^-20 budget (rounded up each) at or
// below which every candidate fits for certain and no order is needed: 31/32 of the budget
// (select_common.glsl's allCandidatesFit says why).
#define RB_ALL_FIT_UNITS 1015808u
#define RB_ALL_FIT_MAX_CANDIDATES 262144u  // 2^18: the rounding bound holds up to here
// The most candidates a selector holds: the walk's sums in no order (include/order_free_sum.glsl)
// are exact up to here.
#define RB_ORDER_FREE_MAX_TERMS 4194304u  // 2^22

// The merge sort (shaders/select/select_block_sort.comp, select_merge.comp): keys sorted
// completely by one workgroup of RB_MERGE_LANES invocations (one SIMD batch on lavapipe),
// and outputs per invocation of each merge pass over the blocks.
#define RB_MERGE_CHUNK 8u  // keys each invocation first sorts with a sorting network
#define RB_MERGE_BLOCK 1024u
#define RB_MERGE_LANES 8u
#define RB_MERGE_SEGMENT 32u
#define RB_MERGE_GROUP 64u        // merge pass workgroup size
#define RB_MERGE_MAX_PASSES 24u   // blocks of 1024 merged up to 2^34 keys

// 16 bytes: one candidate of the GPU selection (select::Candidate).
struct GpuCandidate {
  uint id;
  float cost;
  float value;
  float distance;
};

// The GPU selection's push constants (engine/src/select/gpu_selector.cpp fills them,
// shaders/include/select_common.glsl reads them).
struct SelectPush {
  uvec4 sizes;   // x candidates, y padded (power of two), z policy (RB_SELECT_*), w seed
  uvec4 stage;   // x bitonic k or merge run (the walk in frame mode: RB_APPLY_IN_WALK), y bitonic j or merge pass (the block sort: RB_GATHER_IN_SORT), z which order (0 main, 1 relevance), w `paper` pointers N
                 // (`benefit` with RB_RATE_AUTO in select(): the item groups, max ID / RB_SEGMENT_SLOTS + 1)
  vec4 budget;   // x budget, y frame mode: kappa (budget units per unit of work), z `benefit`'s probe budget,
                 // w frame mode: the work a ray costs (what was never traced is priced at)
  uvec4 walk;    // x `paper` pointer hops per pick (0: as many as fit), y 1: frame mode, z objects, w `benefit`'s rate (RB_RATE_*)
  uvec4 items;   // `benefit`: x effects traced (RB_RT_* bits), y lights, z pixels on screen, w RB_BENEFIT_* and RB_ITEM_COSTS_UNTIMED bits
  vec4 quarterQuality;    // `benefit` with rates: the fill's quality q(1/4) per effect (RB_ITEM_*) this frame,
                          // w: the share of 1/4's skipped pixels a still view traced, for reflections and refractions
  vec4 sixteenthQuality;  // and q(1/16), w 1/16's share (cost_model.cpp's frameFillQualities, frameFillStill)
};

// Frame mode with up to RB_APPLY_IN_WALK_OBJECTS objects: the walk applies the selection to
// them itself (stage.x = RB_APPLY_IN_WALK), a dispatch saved (~0.07 ms on lavapipe, where a
// subgroup applies 512 objects in well under that).
#define RB_APPLY_IN_WALK 1u
#define RB_APPLY_IN_WALK_OBJECTS 512u
// Up to RB_MERGE_BLOCK candidates of a greedy policy: the block sort, which sorts them all in
// one workgroup, lays out the walk's records itself (stage.y = RB_GATHER_IN_SORT).
#define RB_GATHER_IN_SORT 1u

// Policies on the GPU, numbered as select::Policy (engine/src/select/policies.h).
#define RB_SELECT_NONE 0u
#define RB_SELECT_ALL 1u
#define RB_SELECT_PAPER 2u
#define RB_SELECT_DENSITY 3u
#define RB_SELECT_OPTIMAL 4u
#define RB_SELECT_NEAREST 5u
#define RB_SELECT_RANDOM 6u
#define RB_SELECT_BENEFIT 7u  // items, by density of R' (docs/SELECTION.md)

#ifdef __cplusplus
}  // namespace raybudget::gpu
#endif
#endif
