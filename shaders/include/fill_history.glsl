// The history of reduced ray rates for reflections and refractions (include/effect_fill.glsl):
// per pixel what tracing changed against the fallback, traced minus fallback, per path. The
// effects pass writes it where a path was traced and shown this frame (age 0): the fill pass
// (fill_effects.comp) reads this frame's at the traced neighbours of a pixel a rate skipped.
// With the temporal fill (RB_RT_TEMPORAL_FILL, RayTracingSettings::temporalFill) a skipped
// pixel first adds to its fallback the change where it was last traced, reprojected, and the
// fill pass writes it on with its age, before the spatial fill gets the rest. Carrying the change rather than
// the traced value lets the fallback follow the view, as the spatial fill does.
// What the previous frame left at the point is valid only where all of these hold:
//   - it was written by the previous frame, on the same object;
//   - its distance from the previous camera matches the point's within RB_HISTORY_DISTANCE
//     (the surface there is the same, not one in front of it or behind it);
//   - the view direction at the point turned by less than the angle a pixel spans since the
//     change was traced, summed over the frames that carried it: reflections and refractions
//     move with the view, and reprojecting the surface point alone does not follow them (the
//     reflected scene moves by its own depth; measured under a 1-degree-a-frame orbit at
//     320x180, a limit of 1.8 degrees took the court's FLIP from 0.0182 to 0.0164 but
//     ClearCoatTest's from 0.0035 to 0.0037);
//   - it is younger than the item's rate period (1/4: traced three frames ago at most), so a
//     value is carried only until the rate traces the pixel again.
// fillHistory holds two layers per frame parity: 2p the changes as half floats, their ages in
// frames since traced and how far the view turned since (in 255ths of the limit), 2p + 1 the
// object, the distance, the frame that wrote it plus 1 (0, as the image starts, is no frame)
// and the shading normal (octahedral, snorm 2x16): what the fill weighs a source by, without
// reading the G-buffer there.
// A frame reads its predecessor's parity and writes its own.
// The includer includes bindings.glsl and rates.glsl.
#ifndef RB_FILL_HISTORY_GLSL
#define RB_FILL_HISTORY_GLSL
#include "include/reproject.glsl"

#define RB_HISTORY_NONE 255u        // the age of a path with nothing to carry

bool temporalFill() { return (frame.rayTracing.w & RB_RT_TEMPORAL_FILL) != 0u; }

struct History {
  vec3 change[2];  // traced minus fallback: reflection, refraction
  uvec2 age;     // frames since each was traced (RB_HISTORY_NONE: none)
  uvec2 turn;    // how far the view direction turned since, up to this frame (255: the limit)
  float distance;  // of the point from the camera of the frame that wrote it
  uint normal;     // its shading normal, packed (octahedral, snorm 2x16)
};

History noHistory() { return History(vec3[2](vec3(0.0), vec3(0.0)), uvec2(RB_HISTORY_NONE), uvec2(0u), 0.0, 0u); }

// Where the history at `at` in `layer` (2 * parity) was written: its layer + 1 (the object, the
// distance, the frame that wrote it plus 1 and the normal).
uvec4 historyWhere(ivec2 at, uint layer) { return imageLoad(fillHistory, ivec3(at, layer + 1u)); }

// The history at `at` in `layer` whose `where` (historyWhere) the caller has accepted.
History historyAt(ivec2 at, uint layer, uvec4 where) {
  History h = noHistory();
  h.distance = uintBitsToFloat(where.y);
  h.normal = where.w;
  uvec4 terms = imageLoad(fillHistory, ivec3(at, layer));
  vec2 a = unpackHalf2x16(terms.x), b = unpackHalf2x16(terms.y), c = unpackHalf2x16(terms.z);
  h.change[0] = vec3(a, b.x);
  h.change[1] = vec3(b.y, c);
  h.age = uvec2(terms.w & 0xFFu, (terms.w >> 8u) & 0xFFu);
  h.turn = uvec2((terms.w >> 16u) & 0xFFu, terms.w >> 24u);
  return h;
}

// The history at `at` in `layer` (2 * parity), written by frame `tag` - 1 on `objectId`, else
// ages RB_HISTORY_NONE.
History storedHistory(ivec2 at, uint layer, uint tag, uint objectId) {
  uvec4 where = historyWhere(at, layer);
  return where.x == objectId && where.z == tag ? historyAt(at, layer, where) : noHistory();
}

// What this frame wrote at `pixel` of object `objectId` so far (ages RB_HISTORY_NONE where nothing).
History currentHistory(ivec2 pixel, uint objectId) {
  return storedHistory(pixel, (frame.sizeLightsFrame.w & 1u) * 2u, frame.sizeLightsFrame.w + 1u, objectId);
}

// What this frame wrote at `pixel` so far, on whichever object wrote it (`objectId`; RB_NO_OBJECT
// and ages RB_HISTORY_NONE where nothing): one load of where it was written, not two.
History currentHistoryOfWriter(ivec2 pixel, out uint objectId) {
  uint layer = (frame.sizeLightsFrame.w & 1u) * 2u;
  uvec4 where = historyWhere(pixel, layer);
  bool written = where.z == frame.sizeLightsFrame.w + 1u;
  objectId = written ? where.x : RB_NO_OBJECT;
  return written ? historyAt(pixel, layer, where) : noHistory();
}

// What the previous frame left for the point `p` of object `objectId`, or ages RB_HISTORY_NONE.
History previousHistory(vec3 p, uint objectId) {
  History h = noHistory();
  ivec2 at;
  float distance;
  if (!previousPixel(p, at, distance)) return h;
  // The angle between the two view directions from the chord of their unit vectors: exactly 0
  // under a still camera, where acos of their dot product (1 within rounding) read 0.1-0.2 of
  // the limit each frame and, summed over 1/16's 15 carried frames, dropped pixels the rate
  // had traced (a still view at 1/16 kept 0.83 of full rate's FLIP gap on Suzanne, 1/4 0.99).
  vec3 toPrevious = normalize(frame.previousCamera.xyz - p), toCamera = normalize(frame.cameraPositionNear.xyz - p);
  float turned = 2.0 * asin(min(0.5 * length(toPrevious - toCamera), 1.0));
  float limit = pixelAngle();
  if (turned > limit) return h;  // before any load: a moving view turns most points past it
  h = storedHistory(at, ((frame.sizeLightsFrame.w - 1u) & 1u) * 2u, frame.sizeLightsFrame.w, objectId);
  if (!sameDistance(h.distance, distance)) return noHistory();
  h.turn += uint(ceil(turned / limit * 255.0));
  return h;
}

// Whether a change `age` frames old, with the view turned by `turn` since, may stand for a pixel
// its item's `rate` skips this frame.
bool historyFits(uint age, uint turn, uint rate) { return age != RB_HISTORY_NONE && age + 1u < ratePeriod(rate) && turn <= 255u; }

// This frame's history at `pixel`: the changes, their ages (RB_HISTORY_NONE where neither was
// traced nor carried) and turns (at most 255), the object, its distance from the camera and
// its shading normal n.
void writeHistory(ivec2 pixel, vec3 change[2], uvec2 age, uvec2 turn, uint objectId, vec3 p, vec3 n) {
  uint layer = (frame.sizeLightsFrame.w & 1u) * 2u;
  vec3 r = clamp(change[0], vec3(-65504.0), vec3(65504.0)), t = clamp(change[1], vec3(-65504.0), vec3(65504.0));
  imageStore(fillHistory, ivec3(pixel, layer), uvec4(packHalf2x16(r.xy), packHalf2x16(vec2(r.z, t.x)), packHalf2x16(t.yz), age.x | (age.y << 8u) | (turn.x << 16u) | (turn.y << 24u)));
  imageStore(fillHistory, ivec3(pixel, layer + 1u),
             uvec4(objectId, floatBitsToUint(length(frame.cameraPositionNear.xyz - p)), frame.sizeLightsFrame.w + 1u, packSnorm2x16(octEncode(n))));
}

#endif
