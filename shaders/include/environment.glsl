// What the surroundings send along a direction, as the raster fallbacks see them: the
// prefiltered sky, and the reflection probes (cube maps captured from the scene, GGX-
// prefiltered like the sky) sampled with parallax correction against their boxes. The
// includer includes bindings.glsl.
#ifndef RB_ENVIRONMENT_GLSL
#define RB_ENVIRONMENT_GLSL

// The sky, blurred for `roughness` (split-sum prefiltered mips).
vec3 prefiltered(vec3 dir, float roughness) { return textureLod(envMap, dir, roughness * float(RB_ENV_MIPS - 1)).rgb; }

uint reflectionProbeCount() { return frame.probes.x; }

// The probe for a point: the smallest box holding it (RB_NO_PROBE: none does).
uint reflectionProbeAt(vec3 p) {
  uint best = RB_NO_PROBE;
  float bestVolume = 3.4e38;
  for (uint i = 0u; i < reflectionProbeCount(); ++i) {
    vec3 lo = frame.probeBoxMin[i].xyz, hi = frame.probeBoxMax[i].xyz;
    if (any(lessThan(p, lo)) || any(greaterThan(p, hi))) continue;
    vec3 e = hi - lo;
    float volume = e.x * e.y * e.z;
    if (volume < bestVolume) {
      best = i;
      bestVolume = volume;
    }
  }
  return best;
}

// Parallax correction (Lagarde 2012): the ray from `p` along `dir` meets the probe's box at
// a point; the probe is read in the direction from its centre to that point, so that a
// surface near the box's walls reflects them where they are rather than at infinity.
vec3 parallaxDirection(uint probe, vec3 p, vec3 dir) {
  vec3 lo = frame.probeBoxMin[probe].xyz, hi = frame.probeBoxMax[probe].xyz;
  vec3 safe = mix(vec3(1e-6), dir, greaterThan(abs(dir), vec3(1e-6)));
  vec3 far = max((hi - p) / safe, (lo - p) / safe);
  float t = max(min(far.x, min(far.y, far.z)), 0.0);
  return p + dir * t - frame.probeCenter[probe].xyz;
}

// Radiance arriving at `p` from `dir`, blurred for `roughness`: the probe around `p`, else
// (or where the probe's centre is inside an object: alpha, probe_prefilter.comp) the sky.
vec3 surroundings(vec3 p, vec3 dir, float roughness) {
  uint probe = reflectionProbeAt(p);
  if (probe != RB_NO_PROBE) {
    vec4 r = textureLod(reflectionProbes, vec4(parallaxDirection(probe, p, dir), float(probe)), roughness * float(RB_ENV_MIPS - 1));
    if (r.a >= RB_PROBE_MIN_OUTSIDE) return r.rgb;
  }
  return prefiltered(dir, roughness);
}

#endif
