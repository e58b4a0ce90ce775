// Per-item counters of the trace and lighting passes (GpuItemCost): the traversal work and
// the display error that tracing removed, for the `benefit` policy to learn from. The
// includer enables GL_KHR_shader_subgroup_basic, _vote and _arithmetic.
#ifndef RB_ITEM_STATS_GLSL
#define RB_ITEM_STATS_GLSL

// Adds this invocation's work and error per effect (x shadows, y reflections, z refractions)
// to its object's items: lanes of the subgroup on the same object are summed first, then one
// atomic per item with something to add. The error is summed in float over the lanes and
// added in 1/RB_ERROR_UNITS units, rounded.
void addItemCounts(uint objectId, uvec3 work, vec3 error) {
  bool pending = objectId != RB_NO_OBJECT;
  while (subgroupAny(pending)) {
    uint current = subgroupMin(pending ? objectId : RB_NO_OBJECT);
    bool mine = pending && objectId == current;
    uvec3 w = subgroupAdd(mine ? work : uvec3(0u));
    vec3 e = subgroupAdd(mine ? error : vec3(0.0));
    if (mine && subgroupElect()) {
      for (uint k = 0u; k < RB_ITEMS_PER_OBJECT; ++k) {
        uint item = current * RB_ITEMS_PER_OBJECT + k;
        if (w[k] != 0u) atomicAdd(itemCosts[item].work, w[k]);
        uint units = uint(e[k] * RB_ERROR_UNITS + 0.5);
        if (units != 0u) atomicAdd(itemCosts[item].error, units);
      }
    }
    pending = pending && !mine;
  }
}

#endif
