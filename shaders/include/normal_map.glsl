// Tangent-space normal maps without a TANGENT attribute: the cotangent frame (Schueler 2013)
// of the surface's position and texture-coordinate differentials, shared by the G-buffer
// raster (screen-space derivatives, gbuffer.frag) and the tracer's hits (the hit triangle's
// edges, rt_common.glsl's hitSurface), so that a normal-mapped surface shades alike seen
// directly and in a mirror.
#ifndef RB_NORMAL_MAP_GLSL
#define RB_NORMAL_MAP_GLSL

// N perturbed by `mapped` (the map's texel, 0..1 per channel) scaled by `scale` (glTF's
// normalTexture.scale), in the frame of dp1, dp2 (position differentials) and duv1, duv2
// (the map's texture coordinates' differentials, after its transform). N where the texture
// coordinates do not vary.
// T and B below are the gradients of u and v in the plane, times det(dp1, dp2, N): its sign
// is the differentials' orientation about N (negative for the raster's dFdx, dFdy, with
// Vulkan's y down; either for a triangle's edges), so it is taken out. glTF's tangent is the
// direction of increasing u and its bitangent of decreasing v (the texture's +Y is up, its v
// down): NormalTangentMirrorTest's normal-mapped bumps then light as its geometric ones.
vec3 perturbNormal(vec3 N, vec3 mapped, float scale, vec3 dp1, vec3 dp2, vec2 duv1, vec2 duv2) {
  vec3 dp2perp = cross(dp2, N), dp1perp = cross(N, dp1);
  vec3 T = dp2perp * duv1.x + dp1perp * duv2.x;
  vec3 B = dp2perp * duv1.y + dp1perp * duv2.y;
  float len = max(dot(T, T), dot(B, B));
  if (len <= 1e-20) return N;
  float invmax = (dot(cross(dp1, dp2), N) < 0.0 ? -1.0 : 1.0) * inversesqrt(len);
  vec3 t = mapped * 2.0 - 1.0;
  t.xy *= scale;
  vec3 p = mat3(T * invmax, -B * invmax, N) * t;
  return dot(p, p) > 0.0 ? normalize(p) : N;
}

#endif
