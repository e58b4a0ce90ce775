#version 460
#extension GL_GOOGLE_include_directive : require
// One merge pass of the merge sort over sorted runs of stage.x keys (at least a block of
// select_block_sort.comp): runs merged pairwise into runs of 2 stage.x, from the keys into
// the spare buffer (stage.y = 0) or the other way round (1). Each invocation writes
// RB_MERGE_SEGMENT consecutive outputs; no barrier, no shared memory.
#include "include/select_merge.glsl"

layout(local_size_x = 64) in;

void main() {
  uint first = gl_GlobalInvocationID.x * RB_MERGE_SEGMENT;
  mergeRange(first, first + RB_MERGE_SEGMENT, push.stage.x, candidateCount(), push.stage.y != 0u);
}
