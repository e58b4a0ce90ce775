#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_realtime_clock : require
// Coverage: per object, the pixels it covers in the object-ID buffer and the sums of their
// coordinates (for A and the centroid behind P), and per 8x8 tile the objects it shows.
// One invocation per tile sums its pixels in registers for up to RB_TILE_OBJECT_WORDS - 1
// objects and does the atomics once per object and tile (a pixel of a further object adds
// its own and marks the tile crowded). Per-subgroup atomics (one per row of a tile and
// object) cost ~1.4 ms at 640x360 on lavapipe, most of it contention on a few objects'
// records. The 64-bit coordinate sums are kept as lo/hi words with an explicit carry.
#include "include/bindings.glsl"
#include "include/stage_clock.glsl"

layout(local_size_x = RB_GROUP_SIZE) in;
// A specialization: classify the pixels too. A pipeline of its own, used only when asked
// for: its four gathers per quad took the pass from 1.0 to 2.3 ms on the court at 640x360 on
// lavapipe, and even skipped at run time the code cost 0.15 ms.
layout(constant_id = 0) const bool kClassify = false;

void addWide(uint index, uint word, uint value) {
  // word 1: sum x (lo at .y, hi at .z); word 3: sum y (lo at .w, hi at sumYHi.x).
  uint old = word == 1u ? atomicAdd(coverage[index].pixelsSumX.y, value) : atomicAdd(coverage[index].pixelsSumX.w, value);
  if (old + value < old) {
    if (word == 1u) atomicAdd(coverage[index].pixelsSumX.z, 1u);
    else atomicAdd(coverage[index].sumYHi.x, 1u);
  }
}

// Adds pixels of one object (a tile slot's layout below: ID, pixels, sum x, sum y), how
// many of them need reflection rays (low 16 bits of `classes`) and refraction rays (high), and
// how many of those are detailed (shared/selection.h's RB_FILL_DETAIL_COS).
void addCoverage(uvec4 slot, uint classes, uint detailed) {
  if (slot.y == 0u) return;
  atomicAdd(coverage[slot.x].pixelsSumX.x, slot.y);
  addWide(slot.x, 1u, slot.z);
  addWide(slot.x, 3u, slot.w);
  if ((classes & 0xFFFFu) != 0u) atomicAdd(coverage[slot.x].sumYHi.y, classes & 0xFFFFu);
  if ((classes >> 16) != 0u) atomicAdd(coverage[slot.x].sumYHi.z, classes >> 16);
  if (detailed != 0u) atomicAdd(coverage[slot.x].sumYHi.w, detailed);
}

// The classifier: which effects a pixel needs rays for, as the trace shader decides
// (rt_effects.comp): reflections below the roughness cut-off, refractions on transmissive
// non-metals; unlit pixels neither. 1: reflection, 1 << 16: refraction.
uint pixelClasses(float roughness, float transmission, float unlit, float metallic) {
  if (unlit > 0.5) return 0u;
  uint c = roughness <= maxTracedRoughness() ? 1u : 0u;
  if (transmission * (1.0 - metallic) > 0.0) c |= 1u << 16;
  return c;
}

// A tile's object slots (x: object ID, RB_NO_OBJECT while free; y: pixels; z, w: sums of
// x and y: 64 pixels of coordinates below 2^16 fit 32 bits). Explicit variables, not an
// array indexed at run time, which lavapipe would spill.
struct TileSlots {
  uvec4 s0, s1, s2;
  uvec4 classes;  // x, y, z: the slots' pixelClasses sums
  uvec4 detailed; // x, y, z: the slots' detailed pixels
  uint crowded;   // 0 or 1 (a bool member makes glslang emit invalid SPIR-V)
};

void addToSlot(inout uvec4 slot, uint x, uint y) { slot += uvec4(0u, 1u, x, y); }

// The slots are tested one after the other in straight-line code: a chain of calls with
// ||, which would read shorter, measured about 0.07 ms slower on lavapipe (one run of
// alternating builds).
void addPixel(inout TileSlots t, uint id, uint x, uint y, uint classes, uint detailed) {
  if (id == RB_NO_OBJECT) return;
  if (t.s0.x == RB_NO_OBJECT) t.s0.x = id;
  if (id == t.s0.x) {
    addToSlot(t.s0, x, y);
    t.classes.x += classes;
    t.detailed.x += detailed;
    return;
  }
  if (t.s1.x == RB_NO_OBJECT) t.s1.x = id;
  if (id == t.s1.x) {
    addToSlot(t.s1, x, y);
    t.classes.y += classes;
    t.detailed.y += detailed;
    return;
  }
  if (t.s2.x == RB_NO_OBJECT) t.s2.x = id;
  if (id == t.s2.x) {
    addToSlot(t.s2, x, y);
    t.classes.z += classes;
    t.detailed.z += detailed;
    return;
  }
  t.crowded = 1u;
  addCoverage(uvec4(id, 1u, x, y), classes, detailed);
}

// Which pixels of a 2x2 quad (gather order: w, z, x, y) that need reflection or refraction rays
// (`classes`) share the quad with a pixel of their object whose normal is further from theirs
// than RB_FILL_DETAIL_COS (1 each; shared/selection.h). Clamped texels past the image's edge
// repeat the edge pixel, which agrees with itself.
uvec4 detailedPixels(vec2 at, uvec4 ids, uvec4 classes) {
  vec4 nx = textureGather(gNormal, at, 0), ny = textureGather(gNormal, at, 1), nz = textureGather(gNormal, at, 2);
  vec3 n[4] = vec3[4](normalize(vec3(nx.x, ny.x, nz.x)), normalize(vec3(nx.y, ny.y, nz.y)), normalize(vec3(nx.z, ny.z, nz.z)),
                      normalize(vec3(nx.w, ny.w, nz.w)));
  uvec4 detailed = uvec4(0u);
  for (int j = 0; j < 4; ++j) {
    if (classes[j] == 0u) continue;
    for (int k = 0; k < 4; ++k)
      if (k != j && ids[k] == ids[j] && dot(n[j], n[k]) < RB_FILL_DETAIL_COS) detailed[j] = 1u;
  }
  return detailed;
}

void main() {
  stampStageStart();
  uint t = gl_GlobalInvocationID.x;
  uvec2 first, last;
  if (!screenTile(t, first, last)) return;
  TileSlots slots = TileSlots(uvec4(RB_NO_OBJECT, 0u, 0u, 0u), uvec4(RB_NO_OBJECT, 0u, 0u, 0u), uvec4(RB_NO_OBJECT, 0u, 0u, 0u), uvec4(0u), uvec4(0u), 0u);
  // One gather per 2x2 quad: a quarter of the fetches, which were half the pass on lavapipe.
  // At (x + 1, y + 1) / size the gather returns w (x, y), z (x + 1, y), x (x, y + 1) and
  // y (x + 1, y + 1); the sampler clamps, so texels past the image edge are skipped here.
  vec2 texel = 1.0 / vec2(frame.sizeLightsFrame.xy);
  for (uint y = first.y; y < last.y; y += 2u)
    for (uint x = first.x; x < last.x; x += 2u) {
      vec2 at = vec2(x + 1u, y + 1u) * texel;
      uvec4 q = textureGather(gObjectId, at, 0);
      vec4 rough = vec4(1.0), trans = vec4(0.0), unlit = vec4(1.0), metal = vec4(0.0);  // unclassified: no rays
      if (kClassify && !all(equal(q, uvec4(RB_NO_OBJECT)))) {
        // Unlit and metallic only where they decide: a quad of rough opaque pixels (most of
        // a scene) needs two gathers, not four.
        rough = textureGather(gRoughTransIor, at, 0);
        trans = textureGather(gRoughTransIor, at, 1);
        bool glass = any(greaterThan(trans, vec4(0.0)));
        if (glass || any(lessThanEqual(rough, vec4(maxTracedRoughness())))) unlit = textureGather(gRoughTransIor, at, 3);
        if (glass) metal = textureGather(gBaseMetal, at, 3);
      }
      bool right = x + 1u < last.x, below = y + 1u < last.y;
      uvec4 classes = uvec4(pixelClasses(rough.x, trans.x, unlit.x, metal.x), pixelClasses(rough.y, trans.y, unlit.y, metal.y),
                            pixelClasses(rough.z, trans.z, unlit.z, metal.z), pixelClasses(rough.w, trans.w, unlit.w, metal.w));
      // Detail only where a pixel needs reflection or refraction rays: most quads skip the reads.
      uvec4 detailed = kClassify && any(notEqual(classes, uvec4(0u))) ? detailedPixels(at, q, classes) : uvec4(0u);
      addPixel(slots, q.w, x, y, classes.w, detailed.w);
      if (right) addPixel(slots, q.z, x + 1u, y, classes.z, detailed.z);
      if (below) addPixel(slots, q.x, x, y + 1u, classes.x, detailed.x);
      if (right && below) addPixel(slots, q.y, x + 1u, y + 1u, classes.y, detailed.y);
    }
  addCoverage(slots.s0, slots.classes.x, slots.detailed.x);
  addCoverage(slots.s1, slots.classes.y, slots.detailed.y);
  addCoverage(slots.s2, slots.classes.z, slots.detailed.z);
  // The tile's objects for the tile list (shared/config.h): ID + 1 per slot, 0 when free
  // (RB_NO_OBJECT + 1 wraps to 0); every tile writes all its words, so none needs a clear.
  uint base = t * RB_TILE_OBJECT_WORDS;
  tileObjects[base] = slots.s0.x + 1u;
  tileObjects[base + 1u] = slots.s1.x + 1u;
  tileObjects[base + 2u] = slots.s2.x + 1u;
  tileObjects[base + 3u] = slots.crowded;
}
