// The effects pass's temporal fill (RB_RT_TEMPORAL_FILL, RayTracingSettings::temporalFill): a
// pixel that a reduced rate skips this frame takes its reflection and refraction terms from
// the frames where it was last traced, reprojected, before the spatial fill from the tile's
// traced neighbours (include/tile_fill.glsl) gets the rest. What the previous frame left at the
// point is valid only where all of these hold:
//   - it was written by the previous frame, on the same object;
//   - its distance from the previous camera matches the point's within RB_HISTORY_DISTANCE
//     (the surface there is the same, not one in front of it or behind it);
//   - the view direction at the point turned by less than acos(RB_HISTORY_MIN_COS) since the
//     previous frame (reflections and refractions change with it);
//   - it is younger than the item's rate period (1/4: traced three frames ago at most), so a
//     value is carried only until the rate traces the pixel again.
// fillHistory holds two layers per frame parity: 2p the terms as half floats and their ages in
// frames since traced, 2p + 1 the object, the distance and the frame that wrote it. A frame
// reads its predecessor's parity and writes its own, so the pass never reads what it writes.
// The includer includes bindings.glsl and rates.glsl.
#ifndef RB_FILL_HISTORY_GLSL
#define RB_FILL_HISTORY_GLSL

#define RB_HISTORY_NONE 255u        // the age of a path with nothing to carry
#define RB_HISTORY_DISTANCE 0.01    // relative
#define RB_HISTORY_MIN_COS 0.9995   // about 1.8 degrees

bool temporalFill() { return (frame.rayTracing.w & RB_RT_TEMPORAL_FILL) != 0u; }

struct History {
  vec3 term[2];  // reflection, refraction
  uvec2 age;     // frames since each was traced (RB_HISTORY_NONE: none)
};

// The frames after which `rate` traces a pixel again.
uint ratePeriod(uint rate) {
  return rate == RB_RATE_HALF ? 2u : (rate == RB_RATE_QUARTER ? 4u : (rate == RB_RATE_SIXTEENTH ? 16u : 1u));
}

// What the previous frame left for the point `p` of object `objectId`, or ages RB_HISTORY_NONE.
History previousHistory(vec3 p, uint objectId) {
  History h = History(vec3[2](vec3(0.0), vec3(0.0)), uvec2(RB_HISTORY_NONE));
  if (frame.previousCamera.w == 0.0) return h;
  vec4 before = frame.previousViewProj * vec4(p, 1.0);
  if (before.w <= 0.0) return h;
  ivec2 size = ivec2(frame.sizeLightsFrame.xy);
  ivec2 at = ivec2(floor((before.xy / before.w * 0.5 + 0.5) * vec2(size)));
  if (any(lessThan(at, ivec2(0))) || any(greaterThanEqual(at, size))) return h;
  uint layer = ((frame.sizeLightsFrame.w - 1u) & 1u) * 2u;
  uvec4 where = imageLoad(fillHistory, ivec3(at, layer + 1u));
  vec3 toPrevious = frame.previousCamera.xyz - p, toCamera = frame.cameraPositionNear.xyz - p;
  float distance = length(toPrevious);
  if (where.x != objectId || where.z != frame.sizeLightsFrame.w - 1u || abs(uintBitsToFloat(where.y) - distance) > RB_HISTORY_DISTANCE * distance ||
      dot(toPrevious, toCamera) < RB_HISTORY_MIN_COS * distance * length(toCamera))
    return h;
  uvec4 terms = imageLoad(fillHistory, ivec3(at, layer));
  vec2 a = unpackHalf2x16(terms.x), b = unpackHalf2x16(terms.y), c = unpackHalf2x16(terms.z);
  h.term[0] = vec3(a, b.x);
  h.term[1] = vec3(b.y, c);
  h.age = uvec2(terms.w & 0xFFu, (terms.w >> 8u) & 0xFFu);
  return h;
}

// Whether a term `age` frames old may stand for a pixel its item's `rate` skips this frame.
bool historyFits(uint age, uint rate) { return age != RB_HISTORY_NONE && age + 1u < ratePeriod(rate); }

// This frame's history at `pixel`: the terms and their ages (RB_HISTORY_NONE where neither was
// traced nor carried), the object and its distance from the camera.
void writeHistory(ivec2 pixel, vec3 term[2], uvec2 age, uint objectId, vec3 p) {
  uint layer = (frame.sizeLightsFrame.w & 1u) * 2u;
  vec3 r = min(term[0], vec3(65504.0)), t = min(term[1], vec3(65504.0));
  imageStore(fillHistory, ivec3(pixel, layer), uvec4(packHalf2x16(r.xy), packHalf2x16(vec2(r.z, t.x)), packHalf2x16(t.yz), age.x | (age.y << 8u)));
  imageStore(fillHistory, ivec3(pixel, layer + 1u),
             uvec4(objectId, floatBitsToUint(length(frame.cameraPositionNear.xyz - p)), frame.sizeLightsFrame.w, 0u));
}

#endif
