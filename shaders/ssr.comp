#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/gbuffer.glsl"
#include "include/reproject.glsl"
#include "include/depth_pyramid.glsl"

// Screen-space reflections, the reflection fallback's first choice (include/env_fallback.glsl):
// each smooth surface's mirror ray is marched through the min-depth pyramid (Hi-Z: Uludag
// 2014, McGuire and Mara 2014) in screen space, where depth/w varies linearly. Where it meets
// a surface the previous frame's image is read at that surface's place then (reprojected),
// with a confidence that fades at the screen's edges, at the roughness cut-off, for rays
// that leave towards the camera and for back-facing hits; elsewhere the confidence is 0 and
// the reflection probe or the sky stands. Writes ssrImage: rgb the radiance, a the confidence.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

const int kMaxSteps = 80;

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

// How far behind the frame's surface at distance `surfaceW` a ray may pass and still count as
// meeting it: relative to the distance and the scene's size.
float hitShell(float surfaceW) { return 0.02 * surfaceW + 0.002 * frame.ssr.z; }

// The reflection seen on smooth surface `s` (geometric normal ng): rgb radiance, a confidence;
// `hitDistance` how far along the mirror ray the surface it met lies (-1: none).
vec4 reflectionAt(Surface s, vec3 ng, out float hitDistance) {
  hitDistance = -1.0;
  float cutoff = frame.ssr.y;
  vec3 V = normalize(frame.cameraPositionNear.xyz - s.position);
  vec3 R = mirrorDirection(V, s.normal, ng);
  vec3 start = s.position + ng * 1e-3 * length(frame.cameraPositionNear.xyz - s.position);
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
  int levels = textureQueryLevels(depthPyramid) + 1;
  float t = pixels > 1.0 ? marchHiZ(s0, dir, 1.5 / pixels, levels) : -1.0;
  if (t < 0.0) return vec4(0.0);
  vec3 p = s0 + dir * t;
  ivec2 hit = ivec2(p.xy);
  // The ray's distance from the camera (1/w is linear in screen space) against the surface's:
  // a hit only within a thin shell behind the surface, else the ray passed behind it.
  float rayW = 1.0 / mix(1.0 / c0.w, 1.0 / c1.w, t);
  vec4 hitPosition = texelFetch(gPosition, hit, 0);
  float surfaceW = (frame.viewProj * vec4(hitPosition.xyz, 1.0)).w;
  vec3 hitNormal = surfaceNormal(hit);
  bool front = dot(hitNormal, R) < 0.0;
  if (texelFetch(gObjectId, hit, 0).r == RB_NO_OBJECT || rayW - surfaceW >= hitShell(surfaceW) || !front) return vec4(0.0);
  vec2 uv;
  if (!previousUv(hitPosition.xyz, uv)) return vec4(0.0);
  hitDistance = dot(hitPosition.xyz - s.position, R);
  vec2 edge = min(uv, 1.0 - uv), hitEdge = min(p.xy / size, 1.0 - p.xy / size);
  float fade = clamp(min(min(edge.x, edge.y), min(hitEdge.x, hitEdge.y)) / 0.05, 0.0, 1.0);
  fade *= 1.0 - smoothstep(0.6 * cutoff, cutoff, s.roughness);
  fade *= clamp(-dot(hitNormal, R) * 4.0, 0.0, 1.0);  // grazing and back-facing hits fade out
  return vec4(textureLod(previousFrame, uv, 0.0).rgb, fade);
}

// The part of `pixel`'s surface a mirror ray needs (object, position, normal, roughness) where it
// is smooth: four of readSurface's seven fetches, no layers. Rougher pixels, most of a frame,
// read two texels and get nothing written: envReflection reads ssrImage only below the cut-off.
bool readSmoothSurface(ivec2 pixel, out Surface s) {
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return false;
  s.objectId = texelFetch(gObjectId, pixel, 0).r;
  vec4 rti = texelFetch(gRoughTransIor, pixel, 0);
  if (s.objectId == RB_NO_OBJECT || rti.r >= frame.ssr.y || rti.a > 0.5) return false;
  s.roughness = rti.r;
  s.position = surfacePosition(pixel);
  s.normal = surfaceNormal(pixel);
  return true;
}

// The reflection on `s` (geometric normal ng), a neighbour of the surface `marched` whose ray met a surface
// `hitDistance` along it: `s`'s own mirror ray is taken to meet a surface as far along, and
// where the frame has a surface there (within the march's shell) the previous frame is read
// where it showed that point, with the marched pixel's confidence; elsewhere the marched
// pixel's result stands.
vec4 neighbourReflection(Surface s, vec3 ng, vec4 marchedResult, float hitDistance) {
  if (hitDistance <= 0.0) return marchedResult;
  vec3 V = normalize(frame.cameraPositionNear.xyz - s.position);
  vec3 R = mirrorDirection(V, s.normal, ng);
  vec3 p = s.position + R * hitDistance;
  vec4 clip = frame.viewProj * vec4(p, 1.0);
  vec2 size = vec2(frame.sizeLightsFrame.xy);
  vec2 screen = (clip.xy / clip.w * 0.5 + 0.5) * size;
  if (clip.w <= 0.0 || any(lessThan(screen, vec2(0.0))) || any(greaterThanEqual(screen, size))) return marchedResult;
  ivec2 at = ivec2(screen);
  vec3 q = texelFetch(gPosition, at, 0).xyz;
  float surfaceW = (frame.viewProj * vec4(q, 1.0)).w;
  if (texelFetch(gObjectId, at, 0).r == RB_NO_OBJECT || abs(clip.w - surfaceW) >= hitShell(surfaceW)) return marchedResult;
  // One refinement: the point along the ray as far as the surface found there.
  vec2 uv;
  if (!previousUv(s.position + R * max(dot(q - s.position, R), 0.0), uv)) return marchedResult;
  // The texel there, as a marched ray reads it (a filtered read would blur edges).
  return vec4(texelFetch(previousFrame, ivec2(uv * vec2(textureSize(previousFrame, 0))), 0).rgb, marchedResult.a);
}

// One invocation per 2x2 quad: the first pixel of the quad that wants a reflection marches
// its ray; the quad's other pixels of the same surface (object, normal within 18 degrees,
// distance within 2%) reuse its hit distance along their own rays (neighbourReflection); a
// pixel of another surface in the quad marches its own. A quarter of the marches where
// surfaces span several quads.
void main() {
  ivec2 quad = ivec2(gl_GlobalInvocationID.xy) * 2;
  if (any(greaterThanEqual(uvec2(quad), frame.sizeLightsFrame.xy))) return;
  Surface marched;
  vec4 marchedResult = vec4(0.0);
  float hitDistance = -1.0;
  bool haveMarched = false;
  for (int i = 0; i < 4; ++i) {
    ivec2 pixel = quad + ivec2(i & 1, i >> 1);
    Surface s;
    if (!readSmoothSurface(pixel, s)) continue;
    float distance = length(s.position - frame.cameraPositionNear.xyz);
    bool same = haveMarched && s.objectId == marched.objectId && dot(s.normal, marched.normal) > 0.95 &&
                abs(distance - length(marched.position - frame.cameraPositionNear.xyz)) < 0.02 * distance;
    vec3 ng = surfaceGeometricNormal(pixel);
    if (same) {
      imageStore(ssrImage, pixel, neighbourReflection(s, ng, marchedResult, hitDistance));
      continue;
    }
    marchedResult = reflectionAt(s, ng, hitDistance);
    marched = s;
    haveMarched = true;
    imageStore(ssrImage, pixel, marchedResult);
  }
}
