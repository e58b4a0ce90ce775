// Where the previous frame showed a world point (FrameUniforms.previousViewProj): screen-space
// reflections read its image there, the temporal fills their histories. The includer includes
// bindings.glsl.
#ifndef RB_REPROJECT_GLSL
#define RB_REPROJECT_GLSL

// Where the previous frame shows world point `p`, in [0, 1)^2 (false: off its screen).
bool previousUv(vec3 p, out vec2 uv) {
  vec4 before = frame.previousViewProj * vec4(p, 1.0);
  uv = before.xy / before.w * 0.5 + 0.5;
  return before.w > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)));
}

// The previous frame's pixel that shows world point `p` (false: off its screen), and p's
// distance from the previous camera.
bool previousPixel(vec3 p, out ivec2 at, out float distance) {
  at = ivec2(0);
  distance = length(frame.previousCamera.xyz - p);
  vec2 uv;
  if (frame.previousCamera.w == 0.0 || !previousUv(p, uv)) return false;
  ivec2 size = ivec2(frame.sizeLightsFrame.xy);
  at = ivec2(floor(uv * vec2(size)));
  return all(lessThan(at, size));  // (uv just below 1 may round up)
}

// The angle one pixel of this frame spans (the projection may flip y).
float pixelAngle() { return 2.0 * atan(1.0 / abs(frame.proj[1][1])) / float(frame.sizeLightsFrame.y); }

// Whether a history written `stored` from the previous camera shows the same surface as a
// point `distance` from it, not one in front of it or behind it.
#define RB_HISTORY_DISTANCE 0.01  // relative
bool sameDistance(float stored, float distance) { return abs(stored - distance) <= RB_HISTORY_DISTANCE * distance; }

#endif
