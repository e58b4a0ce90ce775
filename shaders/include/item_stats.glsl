// Per-item counters of the trace and lighting passes (GpuItemCost): the traversal work, the
// time and the display error that tracing removed, for the `benefit` policy to learn from.
// The includer enables GL_KHR_shader_subgroup_basic, _vote and _arithmetic.
#ifndef RB_ITEM_STATS_GLSL
#define RB_ITEM_STATS_GLSL

// Adds this invocation's work, ticks, error and counted pixels (1 where the probe or a reduced
// ray rate traced the item here; a full rate's pixels are set at selection), and the ticks and
// count of the pixels its reduced rate skipped (fill_effects.comp), per effect (x shadows, y
// reflections, z refractions) to its object's items: lanes of the subgroup on the same object
// are summed first, then one atomic per item with something to add. The error comes in
// 1/RB_ERROR_UNITS units, whole per pixel (errorUnits).
void addItemCounts(uint objectId, uvec3 work, uvec3 ticks, uvec3 error, uvec3 counted, uvec3 skippedTicks, uvec3 skipped) {
  bool pending = objectId != RB_NO_OBJECT;
  while (subgroupAny(pending)) {
    uint current = subgroupMin(pending ? objectId : RB_NO_OBJECT);
    bool mine = pending && objectId == current;
    uvec3 w = subgroupAdd(mine ? work : uvec3(0u));
    uvec3 t = subgroupAdd(mine ? ticks : uvec3(0u));
    uvec3 e = subgroupAdd(mine ? error : uvec3(0u));
    uvec3 p = subgroupAdd(mine ? counted : uvec3(0u));
    uvec3 st = subgroupAdd(mine ? skippedTicks : uvec3(0u));
    uvec3 sp = subgroupAdd(mine ? skipped : uvec3(0u));
    if (mine && subgroupElect()) {
      for (uint k = 0u; k < RB_ITEMS_PER_OBJECT; ++k) {
        uint item = current * RB_ITEMS_PER_OBJECT + k;
        if (w[k] != 0u) atomicAdd(itemCosts[item].work, w[k]);
        if (t[k] != 0u) atomicAdd(itemCosts[item].ticks, t[k]);
        if (e[k] != 0u) atomicAdd(itemCosts[item].error, e[k]);
        if (p[k] != 0u) atomicAdd(itemCosts[item].pixels, p[k]);
        if (st[k] != 0u) atomicAdd(itemCosts[item].skippedTicks, st[k]);
        if (sp[k] != 0u) atomicAdd(itemCosts[item].skippedPixels, sp[k]);
      }
    }
    pending = pending && !mine;
  }
}

void addItemCounts(uint objectId, uvec3 work, uvec3 ticks, uvec3 error, uvec3 counted) {
  addItemCounts(objectId, work, ticks, error, counted, uvec3(0u), uvec3(0u));
}

// A pixel's errors (each in [0, 1]) in whole 1/RB_ERROR_UNITS units, rounded with a dither
// fixed per pixel. Whole units per pixel sum alike whichever lanes share a subgroup, which
// the tile list's atomics decide (a float sum per subgroup, rounded once, gave two identical
// frames benefits a few ULP apart); the dither keeps errors below a unit from rounding to 0.
uvec3 errorUnits(vec3 error, ivec2 pixel) {
  uint h = uint(pixel.x) * 0x8DA6B343u ^ uint(pixel.y) * 0xD8163841u;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  float dither = float(h >> 8) * (1.0 / 16777216.0);
  return uvec3(floor(clamp(error, 0.0, 1.0) * RB_ERROR_UNITS + dither));
}

// The subgroup clock (VK_KHR_shader_clock): the subgroup's lanes run together, so a span
// timed on it is the subgroup's time; each of the `sharing` lanes that caused it is charged
// an equal part, in RB_CLOCK_UNIT ticks.
uint clockNow() { return clock2x32ARB().x; }
uint clockShare(uint start, uint end, uint sharing) { return sharing == 0u ? 0u : (end - start) / (sharing * RB_CLOCK_UNIT); }

#endif
