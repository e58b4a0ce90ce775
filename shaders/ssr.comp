#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/gbuffer.glsl"

// Screen-space reflections, the reflection fallback's first choice (include/env_fallback.glsl):
// each smooth surface's mirror ray is marched through the min-depth pyramid (Hi-Z: Uludag
// 2014, McGuire and Mara 2014) in screen space, where depth/w varies linearly. Where it meets
// a surface the previous frame's image is read at that surface's place then (reprojected),
// with a confidence that fades at the screen's edges, at the roughness cut-off, for rays
// that leave towards the camera and for back-facing hits; elsewhere the confidence is 0 and
// the reflection probe or the sky stands. Writes ssrImage: rgb the radiance, a the confidence.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

const int kMaxSteps = 80;

float pyramidDepth(ivec2 cell, int level) { return texelFetch(depthPyramid, cell, level).r; }

// Marches p(t) = origin + dir * t, t in [tStart, 1], in (pixel x, pixel y, depth) space;
// returns the t where it first passes behind the nearest depth of a level-0 texel, or -1.
float marchHiZ(vec3 origin, vec3 dir, float tStart, int levels) {
  vec2 size = vec2(frame.sizeLightsFrame.xy);
  float t = tStart;
  int level = 0;
  for (int i = 0; i < kMaxSteps; ++i) {
    if (t > 1.0) return -1.0;
    vec3 p = origin + dir * t;
    if (any(lessThan(p.xy, vec2(0.0))) || any(greaterThanEqual(p.xy, size))) return -1.0;
    float cellSize = float(1 << level);
    ivec2 cell = ivec2(p.xy / cellSize);
    float nearest = pyramidDepth(cell, level);
    // Where the ray leaves the cell, and where it reaches the cell's nearest depth.
    vec2 bound = (vec2(cell) + vec2(greaterThan(dir.xy, vec2(0.0)))) * cellSize;
    vec2 tBound = mix(vec2(1e30), (bound - origin.xy) / dir.xy, greaterThan(abs(dir.xy), vec2(1e-9)));
    float tExit = min(tBound.x, tBound.y) + 1e-4 / max(length(dir.xy), 1e-9);
    if (p.z < nearest) {
      float tPlane = dir.z > 0.0 ? (nearest - origin.z) / dir.z : 1e30;
      if (tPlane < tExit) {  // it reaches the nearest depth inside this cell: look closer
        t = max(tPlane, t);
        if (level == 0) return t;
        --level;
      } else {
        t = tExit;
        level = min(level + 1, levels - 1);
      }
    } else if (level == 0) {
      return t;  // behind the texel's surface
    } else {
      --level;
    }
  }
  return -1.0;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  // Rougher pixels (most of a frame) read two texels and write nothing: envReflection reads
  // ssrImage only below the cut-off.
  float cutoff = frame.ssr.y;
  vec4 rti = texelFetch(gRoughTransIor, pixel, 0);
  if (texelFetch(gObjectId, pixel, 0).r == RB_NO_OBJECT || rti.r >= cutoff || rti.a > 0.5) return;
  vec4 result = vec4(0.0);
  Surface s;
  if (readSurface(pixel, s)) {
    vec3 V = normalize(frame.cameraPositionNear.xyz - s.position);
    vec3 R = reflect(-V, s.normal);
    vec3 start = s.position + s.normal * 1e-3 * length(frame.cameraPositionNear.xyz - s.position);
    // The ray's far end, pulled in front of the near plane where the ray comes back towards the camera.
    float reach = frame.ssr.z;
    vec4 c0 = frame.viewProj * vec4(start, 1.0), c1 = frame.viewProj * vec4(start + R * reach, 1.0);
    float near = frame.cameraPositionNear.w;
    if (c1.w < near) {
      reach *= (c0.w - near) / max(c0.w - c1.w, 1e-6) * 0.99;
      c1 = frame.viewProj * vec4(start + R * reach, 1.0);
    }
    vec2 size = vec2(frame.sizeLightsFrame.xy);
    vec3 s0 = vec3((c0.xy / c0.w * 0.5 + 0.5) * size, c0.z / c0.w), s1 = vec3((c1.xy / c1.w * 0.5 + 0.5) * size, c1.z / c1.w);
    vec3 dir = s1 - s0;
    float pixels = max(abs(dir.x), abs(dir.y));
    int levels = textureQueryLevels(depthPyramid);
    float t = pixels > 1.0 ? marchHiZ(s0, dir, 1.5 / pixels, levels) : -1.0;
    if (t >= 0.0) {
      vec3 p = s0 + dir * t;
      ivec2 hit = ivec2(p.xy);
      // The ray's distance from the camera (1/w is linear in screen space) against the surface's:
      // a hit only within a thin shell behind the surface, else the ray passed behind it.
      float rayW = 1.0 / mix(1.0 / c0.w, 1.0 / c1.w, t);
      vec4 hitPosition = texelFetch(gPosition, hit, 0);
      float surfaceW = (frame.viewProj * vec4(hitPosition.xyz, 1.0)).w;
      vec3 hitNormal = normalize(texelFetch(gNormal, hit, 0).xyz);
      bool front = dot(hitNormal, R) < 0.0;
      float shell = 0.02 * surfaceW + 0.002 * frame.ssr.z;  // relative to the distance and the scene's size
      if (texelFetch(gObjectId, hit, 0).r != RB_NO_OBJECT && rayW - surfaceW < shell && front) {
        vec4 before = frame.previousViewProj * vec4(hitPosition.xyz, 1.0);
        vec2 uv = before.xy / before.w * 0.5 + 0.5;
        if (before.w > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)))) {
          vec2 edge = min(uv, 1.0 - uv), hitEdge = min(p.xy / size, 1.0 - p.xy / size);
          float fade = clamp(min(min(edge.x, edge.y), min(hitEdge.x, hitEdge.y)) / 0.05, 0.0, 1.0);
          fade *= 1.0 - smoothstep(0.6 * cutoff, cutoff, s.roughness);
          fade *= clamp(-dot(hitNormal, R) * 4.0, 0.0, 1.0);  // grazing and back-facing hits fade out
          result = vec4(textureLod(previousFrame, uv, 0.0).rgb, fade);
        }
      }
    }
  }
  imageStore(ssrImage, pixel, result);
}
