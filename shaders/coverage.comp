#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Coverage: per object, the pixels it covers in the object-ID buffer and the sums of their
// coordinates (for A and the centroid behind P). Lanes of a subgroup that see the same
// object are reduced together, so one lane per object and subgroup does the atomics; the
// 64-bit coordinate sums are kept as lo/hi words with an explicit carry.
#include "include/bindings.glsl"

layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

void addWide(uint index, uint word, uint value) {
  // word 1: sum x (lo at .y, hi at .z); word 3: sum y (lo at .w, hi at sumYHi.x).
  uint old = word == 1u ? atomicAdd(coverage[index].pixelsSumX.y, value) : atomicAdd(coverage[index].pixelsSumX.w, value);
  if (old + value < old) {
    if (word == 1u) atomicAdd(coverage[index].pixelsSumX.z, 1u);
    else atomicAdd(coverage[index].sumYHi.x, 1u);
  }
}

// Adds an object to the tile's set (shared/config.h), or marks the set full.
void noteTileObject(uint tile, uint id) {
  uint base = tile * RB_TILE_OBJECT_WORDS;
  for (uint s = 0u; s + 1u < RB_TILE_OBJECT_WORDS; ++s) {
    uint old = atomicCompSwap(tileObjects[base + s], 0u, id + 1u);
    if (old == 0u || old == id + 1u) return;
  }
  tileObjects[base + RB_TILE_OBJECT_WORDS - 1u] = 1u;
}

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  uint tile = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;  // a workgroup is a tile
  bool inside = p.x < frame.sizeLightsFrame.x && p.y < frame.sizeLightsFrame.y;
  uint id = inside ? texelFetch(gObjectId, ivec2(p), 0).r : RB_NO_OBJECT;
  bool pending = id != RB_NO_OBJECT;
  // One round per distinct object in the subgroup (usually one or two).
  while (subgroupAny(pending)) {
    uint current = subgroupMin(pending ? id : RB_NO_OBJECT);
    bool mine = pending && id == current;
    uint pixels = subgroupAdd(mine ? 1u : 0u);
    uint sumX = subgroupAdd(mine ? p.x : 0u);
    uint sumY = subgroupAdd(mine ? p.y : 0u);
    if (subgroupElect()) {
      atomicAdd(coverage[current].pixelsSumX.x, pixels);
      addWide(current, 1u, sumX);
      addWide(current, 3u, sumY);
      noteTileObject(tile, current);
    }
    pending = pending && !mine;
  }
}
