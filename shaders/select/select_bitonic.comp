#version 460
#extension GL_GOOGLE_include_directive : require
// One step of a bitonic sort of the key array (order, or relevance with stage.z = 1),
// ascending. stage.y = j >= 1024: one compare-exchange distance over the whole array;
// stage.y = 0: every distance j < 1024 of stage k at once, inside 1024-element blocks in
// shared memory; stage.x = 0 as well: every stage k <= 1024 at once (sorts each block).
// 36 dispatches for 2^17 keys, one for 1024 or fewer. (Blocks of 128 cost less per
// dispatch on lavapipe, where barriers switch between the workgroup's SIMD batches, but
// need more dispatches: slower from 1k keys on.)
#include "include/select_common.glsl"

layout(local_size_x = 512) in;

shared uvec2 block[1024];

uvec2 load(uint i) { return push.stage.z == 0u ? order[i] : relevance[i]; }
void store(uint i, uvec2 v) {
  if (push.stage.z == 0u) order[i] = v;
  else relevance[i] = v;
}

void main() {
  uint k = push.stage.x, j = push.stage.y, t = gl_GlobalInvocationID.x, size = sortSize();
  if (k > size) return;  // stages past the candidates' size: the prefix is sorted already
  if (j >= 1024u) {
    uint i = 2u * j * (t / j) + (t % j), l = i + j;
    if (l >= size) return;
    uvec2 a = load(i), b = load(l);
    bool ascending = (i & k) == 0u;
    if (keyLess(b, a) == ascending) {
      store(i, b);
      store(l, a);
    }
    return;
  }
  uint base = gl_WorkGroupID.x * 1024u, lt = gl_LocalInvocationID.x;
  if (base >= size) return;  // the whole workgroup: no barrier is left waiting
  block[lt] = load(base + lt);
  block[lt + 512u] = load(base + lt + 512u);
  uint kFirst = k == 0u ? 2u : k, kLast = k == 0u ? 1024u : k;
  for (uint kk = kFirst; kk <= kLast; kk *= 2u) {
    for (uint jj = min(kk / 2u, 512u); jj > 0u; jj /= 2u) {
      barrier();
      uint i = 2u * jj * (lt / jj) + (lt % jj), l = i + jj;
      bool ascending = ((base + i) & kk) == 0u;
      uvec2 a = block[i], b = block[l];
      if (keyLess(b, a) == ascending) {
        block[i] = b;
        block[l] = a;
      }
    }
  }
  barrier();
  store(base + lt, block[lt]);
  store(base + lt + 512u, block[lt + 512u]);
}
