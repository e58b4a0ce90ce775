// Where the previous frame showed a world point (FrameUniforms.previousViewProj): screen-space
// reflections read its image there, the effects pass's temporal fill its history. The includer
// includes bindings.glsl.
#ifndef RB_REPROJECT_GLSL
#define RB_REPROJECT_GLSL

// Where the previous frame shows world point `p`, in [0, 1)^2 (false: off its screen).
bool previousUv(vec3 p, out vec2 uv) {
  vec4 before = frame.previousViewProj * vec4(p, 1.0);
  uv = before.xy / before.w * 0.5 + 0.5;
  return before.w > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)));
}

#endif
