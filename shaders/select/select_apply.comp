#version 460
#extension GL_GOOGLE_include_directive : require
// Frame mode, after the walk: include/select_apply.glsl per object (the walk does it itself
// for few objects).
#include "shared/config.h"
#include "include/select_common.glsl"
#include "include/select_apply.glsl"

layout(local_size_x = RB_GROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < push.walk.z) applySelection(i);
}
