#version 460
#extension GL_GOOGLE_include_directive : require
// The same order as the bitonic sort, by one invocation: heapsort of the candidates' keys
// (order, or relevance with stage.z = 1). On a CPU device (lavapipe) one invocation's
// n log n steps cost less than the bitonic sort's barrier-heavy shared-memory stages; a GPU
// uses the bitonic sort. Keys are a total order, so both give the same result.
#include "include/select_common.glsl"

layout(local_size_x = 1) in;

uvec4 load(uint i) { return push.stage.z == 0u ? order[i] : relevance[i]; }
void store(uint i, uvec4 v) {
  if (push.stage.z == 0u) order[i] = v;
  else relevance[i] = v;
}

// Moves the key at `root` down the max-heap of the first `n` keys.
void siftDown(uint root, uint n) {
  uvec4 v = load(root);
  while (true) {
    uint child = 2u * root + 1u;
    if (child >= n) break;
    uvec4 c = load(child);
    if (child + 1u < n) {
      uvec4 d = load(child + 1u);
      if (keyLess(c, d)) {
        ++child;
        c = d;
      }
    }
    if (!keyLess(v, c)) break;
    store(root, c);
    root = child;
  }
  store(root, v);
}

void main() {
  uint n = candidateCount();
  if (n < 2u) return;
  for (uint i = n / 2u; i > 0u; --i) siftDown(i - 1u, n);
  for (uint end = n - 1u; end > 0u; --end) {
    uvec4 top = load(0u);
    store(0u, load(end));
    store(end, top);
    siftDown(0u, end);
  }
}
