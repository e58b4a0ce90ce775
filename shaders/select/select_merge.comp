#version 460
#extension GL_GOOGLE_include_directive : require
// Merge pass stage.y of the merge sort, over sorted runs of stage.x keys (at least a block
// of select_block_sort.comp): runs merged pairwise into runs of 2 stage.x, from the keys
// into the spare buffer or the other way round, so that the last pass writes the keys.
// Dispatched indirectly (select_block_sort.comp sizes it for the candidates, and empties a
// pass whose runs would already hold them all). Each
// invocation writes RB_MERGE_SEGMENT consecutive outputs; no barrier, no shared memory.
#include "include/select_merge.glsl"

layout(local_size_x = RB_MERGE_GROUP) in;

void main() {
  uint n = candidateCount(), run = push.stage.x, first = gl_GlobalInvocationID.x * RB_MERGE_SEGMENT;
  if (run >= n) return;
  bool fromSpare = ((mergePasses(n) - push.stage.y) & 1u) != 0u;  // the last pass reads the spare buffer
  mergeRange(first, first + RB_MERGE_SEGMENT, run, n, fromSpare);
}
