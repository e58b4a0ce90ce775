#version 460
#extension GL_GOOGLE_include_directive : require
// The bitonic sort's keys: each candidate's (select_common.glsl's candidateKey), and
// padding (all ones, sorted last) up to the power-of-two size the sort needs. The merge
// sort computes its keys itself (select_block_sort.comp).
#include "shared/config.h"
#include "include/select_common.glsl"

layout(local_size_x = RB_KEYS_GROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.sizes.y) return;
  uvec2 key = candidateKey(i, push.stage.z);
  if (push.stage.z == 0u) order[i] = key;
  else relevance[i] = key;
}
