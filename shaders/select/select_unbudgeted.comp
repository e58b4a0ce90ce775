#version 460
#extension GL_GOOGLE_include_directive : require
// The select pass for the unbudgeted policies: push x = object count, y = 0 none, 1 all
// (every object with pixels on screen), z the items' ray rate (RB_RATE_*). The budgeted policies select in
// shaders/select/ (engine/src/select/gpu_selector.h), then the tile list follows.
#include "include/bindings.glsl"

layout(local_size_x = RB_GROUP_SIZE) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.objectMaterial.x) return;
  bool all = push.objectMaterial.y == 1u;
  uint rate = push.objectMaterial.z;
  uint rates = rate << RB_RATE_SHIFT | rate << (RB_RATE_SHIFT + 2u) | rate << (RB_RATE_SHIFT + 4u);
  selected[i] = all && floatBitsToUint(objectRecords[i].crCandidatePixels.w) > 0u ? RB_ITEMS_ALL | rates : 0u;
  // The item counters start over (`classified` measures them; ObjectMetrics reads this frame's).
  for (uint k = 0u; k < RB_ITEMS_PER_OBJECT; ++k) {
    uint item = i * RB_ITEMS_PER_OBJECT + k;
    itemCosts[item].work = 0u;
    itemCosts[item].ticks = 0u;
    itemCosts[item].error = 0u;
  }
  if (i == 0u) itemCosts[uint(itemCosts.length()) - 1u].selectedLast = 0u;  // no partial item (include/probe.glsl)
}
