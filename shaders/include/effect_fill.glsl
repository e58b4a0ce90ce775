// The fill of the reflections and refractions a reduced ray rate skipped (include/rates.glsl),
// in a pass of its own after the effects pass (fill_effects.comp): at a pixel its reflection
// (refraction) item's rate skipped this frame, first, with the temporal fill, what tracing
// changed there when last traced, reprojected (include/fill_history.glsl); else the weighted
// mean (include/fill_weights.glsl) of what tracing changed against the fallback at the pixels
// around it that the rate traced on the same object this frame (their history, age 0); added
// to this pixel's fallback in reflectionImage (refractionImage). Filling the change rather
// than the radiance keeps this pixel's own environment where the neighbours' rays escaped to
// it. It reads across tiles. Where no neighbour qualifies the fallback stays.
// The includer includes bindings.glsl, gbuffer.glsl, rates.glsl and probe.glsl.
#ifndef RB_EFFECT_FILL_GLSL
#define RB_EFFECT_FILL_GLSL
#include "include/fill_history.glsl"
#include "include/fill_weights.glsl"

// Whether the frame traces the surface's reflection (x) and transmission (y) path where its
// item is traced: `paths` (RB_RT_* bits) hold it, the effect is on, and the surface is smooth
// enough (transmissive).
bvec2 surfacePaths(Surface s, uint paths) {
  uint effects = frame.rayTracing.x & paths;
  return bvec2((effects & RB_RT_REFLECTIONS) != 0u && s.roughness <= maxTracedRoughness(),
               (effects & RB_RT_REFRACTIONS) != 0u && s.transmission * (1.0 - s.metallic) > 0.0);
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

// Adds a source's change per path in `use`, at weight w, to the fill's sums.
void addSource(bool use[2], float w, vec3 change[2], inout vec3 sum[2], inout vec3 squares[2], inout float total[2]) {
  for (int path = 0; path < 2; ++path)
    if (use[path]) {
      sum[path] += w * change[path];
      squares[path] += w * change[path] * change[path];
      total[path] += w;
    }
}

// Adds to the sums of the paths in `want` (0 reflection, 1 refraction) what tracing changed at
// the pixels around `pixel` that `rate` traced this frame on c's object. Their history holds
// all the fill reads there: the object, whether the path was traced (age 0), the change, and
// the point's distance and normal for its weight (the position on the pixel's view ray at that
// distance), so a source costs two image loads and no G-buffer read.
void gatherChanges(ivec2 pixel, FillCentre c, uint rate, bool want[2], inout vec3 sum[2], inout vec3 squares[2], inout float total[2]) {
  ivec2 at[4];
  float near[4];
  fillLattice(pixel, rate, at, near);
  for (int k = 0; k < 4; ++k) {
    if (near[k] <= 0.0) continue;
    History h = currentHistory(at[k], c.objectId);
    bool use[2] = bool[2](want[0] && h.age[0] == 0u, want[1] && h.age[1] == 0u);
    if (!use[0] && !use[1]) continue;
    vec3 position = frame.cameraPositionNear.xyz + viewDirection(at[k]) * h.distance;
    addSource(use, near[k] * fillSimilarity(c, position, octDecode(unpackSnorm2x16(h.normal))), h.change, sum, squares, total);
  }
}

// 1/16's lattice of traced pixels as the fill of a 4x4 block of the screen reads it
// (fill_effects.comp): the block's pixels fall into at most four of the lattice's cells, and
// each cell's four corner points are read once for its pixels (the history, the position on
// the view ray and the decoded normal each), where the pixels one at a time read and decoded
// four each (60 a block: the larger part of the fill's time at 1/16 on lavapipe). What a corner
// holds is what currentHistory gives a pixel of its object.
struct LatticeSource {
  uint objectId;  // RB_NO_OBJECT: off the screen, or nothing traced there this frame
  uint fresh;     // bit p: path p was traced there this frame (age 0)
  vec3 change0, change1;
  vec3 position;  // on the point's view ray at the distance its history holds
  vec3 normal;
};

LatticeSource latticeSource(ivec2 q) {
  LatticeSource s = LatticeSource(RB_NO_OBJECT, 0u, vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), frame.sizeLightsFrame.xy))) return s;
  uint objectId;
  History h = currentHistoryOfWriter(q, objectId);
  s.fresh = (h.age[0] == 0u ? 1u : 0u) | (h.age[1] == 0u ? 2u : 0u);
  if (s.fresh == 0u) return s;
  s.objectId = objectId;
  s.change0 = h.change[0];
  s.change1 = h.change[1];
  s.position = frame.cameraPositionNear.xyz + viewDirection(q) * h.distance;
  s.normal = octDecode(unpackSnorm2x16(h.normal));
  return s;
}

// A lattice cell: its corner at `below` and the three to the right and down (4 pixels apart),
// read when a pixel first needs them. Separate members, not an array: indexed at run time,
// lavapipe keeps an array in memory (a quarter of the fill's time at 1/16).
struct LatticeCell {
  ivec2 below;
  bool read;
  LatticeSource s00, s10, s01, s11;
};

LatticeCell latticeCell(ivec2 below) {
  LatticeSource none = LatticeSource(RB_NO_OBJECT, 0u, vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
  return LatticeCell(below, false, none, none, none, none);
}

// Adds a corner `d` pixels from the pixel to the sums of the paths in `want` (gatherChanges'
// weights and sums for 1/16).
void addLatticeSource(LatticeSource src, ivec2 d, FillCentre c, bool want[2], inout vec3 sum[2], inout vec3 squares[2], inout float total[2]) {
  if (src.objectId != c.objectId) return;
  bool use[2] = bool[2](want[0] && (src.fresh & 1u) != 0u, want[1] && (src.fresh & 2u) != 0u);
  if (!use[0] && !use[1]) return;
  addSource(use, latticeNearness(d, true) * fillSimilarity(c, src.position, src.normal), vec3[2](src.change0, src.change1), sum, squares, total);
}

// gatherChanges at 1/16 for a pixel of `cell`: the same sources in the same order, so the same sums.
void gatherLattice(ivec2 pixel, FillCentre c, bool want[2], inout LatticeCell cell, inout vec3 sum[2], inout vec3 squares[2], inout float total[2]) {
  if (!cell.read) {
    cell.s00 = latticeSource(cell.below);
    cell.s10 = latticeSource(cell.below + ivec2(4, 0));
    cell.s01 = latticeSource(cell.below + ivec2(0, 4));
    cell.s11 = latticeSource(cell.below + ivec2(4, 4));
    cell.read = true;
  }
  ivec2 d = cell.below - pixel;
  addLatticeSource(cell.s00, d, c, want, sum, squares, total);
  addLatticeSource(cell.s10, d + ivec2(4, 0), c, want, sum, squares, total);
  addLatticeSource(cell.s01, d + ivec2(0, 4), c, want, sum, squares, total);
  addLatticeSource(cell.s11, d + ivec2(4, 4), c, want, sum, squares, total);
}

void addToPath(ivec2 pixel, int path, vec3 change) {
  if (path == 0) imageStore(reflectionImage, pixel, vec4(imageLoad(reflectionImage, pixel).rgb + change, 1.0));
  else imageStore(refractionImage, pixel, vec4(imageLoad(refractionImage, pixel).rgb + change, 1.0));
}

// Fills the pixel's paths (x reflection, y refraction) that their items' reduced rates skipped
// this frame; returns them. `objectId` (an object) and `sel` (its selection in the pixel's tile):
// the pixel's; `cell`: 1/16's lattice cell that holds it. `past`: the fill is past its deadline (include/deadline_cut.glsl), so it fills
// nothing and `left` says whether an item's rate skipped the pixel (the fill's pixels the
// deadline left).
bvec2 fillEffects(ivec2 pixel, uint objectId, Selection sel, bool past, inout LatticeCell cell, out bool left) {
  left = false;
  uint rates[2] = uint[2](itemRate(sel, RB_ITEM_REFLECTIONS), itemRate(sel, RB_ITEM_REFRACTIONS));
  bool skipped[2] = bool[2](itemSelected(sel, RB_ITEM_REFLECTIONS) && !rateTraces(rates[0], pixel),
                            itemSelected(sel, RB_ITEM_REFRACTIONS) && !rateTraces(rates[1], pixel));
  if (!skipped[0] && !skipped[1]) return bvec2(false);
  left = past;
  if (past) return bvec2(false);
  Surface s;
  if (!readSurfacePoint(pixel, objectId, s)) return bvec2(false);
  bvec2 paths = surfacePaths(s, RB_RT_REFLECTIONS | RB_RT_REFRACTIONS);
  bool pending[2] = bool[2](skipped[0] && paths.x, skipped[1] && paths.y);
  bvec2 filled = bvec2(pending[0], pending[1]);
  if (!any(filled)) return filled;
  History now = noHistory();
  bool carried = false;
  if (temporalFill()) {
    History h = previousHistory(s.position, objectId);
    for (int path = 0; path < 2; ++path)
      if (pending[path] && historyFits(h.age[path], h.turn[path], rates[path])) {
        // The other path, where its item's rate traced it here, is kept where the history is written.
        if (!carried && itemSelected(sel, path == 0 ? RB_ITEM_REFRACTIONS : RB_ITEM_REFLECTIONS) && !skipped[1 - path])
          now = currentHistory(pixel, objectId);
        addToPath(pixel, path, h.change[path]);
        now.change[path] = h.change[path];
        now.age[path] = h.age[path] + 1u;
        now.turn[path] = h.turn[path];
        pending[path] = false;
        carried = true;
      }
  }
  if (pending[0] || pending[1]) {
    FillCentre c = fillCentre(objectId, s.position, s.normal);
    vec3 sum[2] = vec3[2](vec3(0.0), vec3(0.0)), squares[2] = vec3[2](vec3(0.0), vec3(0.0));
    float total[2] = float[2](0.0, 0.0);
    // Both paths from one gather where their rates agree.
    bool both = pending[0] && pending[1] && rates[0] == rates[1];
    if (pending[0]) {
      if (rates[0] == RB_RATE_SIXTEENTH) gatherLattice(pixel, c, bool[2](true, both), cell, sum, squares, total);
      else gatherChanges(pixel, c, rates[0], bool[2](true, both), sum, squares, total);
    }
    if (pending[1] && !both) {
      if (rates[1] == RB_RATE_SIXTEENTH) gatherLattice(pixel, c, bool[2](false, true), cell, sum, squares, total);
      else gatherChanges(pixel, c, rates[1], bool[2](false, true), sum, squares, total);
    }
    for (int path = 0; path < 2; ++path)
      if (pending[path] && total[path] >= RB_FILL_MIN_WEIGHT) addToPath(pixel, path, shrunkMean(sum[path], squares[path], total[path]));
  }
  if (carried) writeHistory(pixel, now.change, now.age, now.turn, objectId, s.position, s.normal);
  return filled;
}

#endif
