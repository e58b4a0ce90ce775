#version 460
#extension GL_GOOGLE_include_directive : require
// Frame mode, after the walk: the selected candidates' objects are marked in the frame's
// selection (zeroed by the host before), and (second dispatch, stage.z = 1) each object's
// S for the next frame's relevance is set from it, and its traced pixel count noted.
#include "include/select_common.glsl"

layout(local_size_x = 64) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (push.stage.z == 0u) {
    if (i < candidateCount() && selectedFlags[i] != 0u) selected[candidates[i].id] = 1u;
  } else if (i < push.walk.z) {
    float s = selected[i] != 0u ? 1.0 : 0.0;
    if (s != params[i].kqiS.w) atomicAdd(result2.x, 1u);
    params[i].kqiS.w = s;
    // The pixels the trace passes will count work over, for next frame's learning.
    costs[i].pixels = selected[i] != 0u ? floatBitsToUint(records[i].crCandidatePixels.w) : 0u;
  }
}
