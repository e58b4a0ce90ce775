#version 460
#extension GL_GOOGLE_include_directive : require
// Frame mode, after the walk has marked the selected objects in the frame's selection:
// each object's S for the next frame's relevance is set from it, and its traced pixel
// count noted.
#include "include/select_common.glsl"

layout(local_size_x = 64) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < push.walk.z) {
    float s = selected[i] != 0u ? 1.0 : 0.0;
    if (s != params[i].kqiS.w) atomicAdd(result2.x, 1u);
    params[i].kqiS.w = s;
    // The pixels the trace passes will count work over, for next frame's learning.
    costs[i].pixels = selected[i] != 0u ? floatBitsToUint(records[i].crCandidatePixels.w) : 0u;
  }
}
