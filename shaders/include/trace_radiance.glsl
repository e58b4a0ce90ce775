// Radiance along a ray, by closest-hit tracing: what a traced reflection or refraction
// shows, and what a reflection probe captures (probe_capture.comp). The includer includes
// rt_common.glsl and environment.glsl.
#ifndef RB_TRACE_RADIANCE_GLSL
#define RB_TRACE_RADIANCE_GLSL

// Whether traceRadiance's first hit was the back of a one-sided surface (the ray started
// inside a closed object), and how far along the ray it was (1e30: none).
bool rbFirstHitInside = false;
float rbFirstHitDistance = 1e30;

// Closest hit along the ray, alpha masks respected.
bool traceClosest(vec3 origin, vec3 dir, out RayQuery q, inout uint work) {
  ++rbRays;
  rqInitialize(q, 0u, 0xFFu, origin, 0.0, dir, 1e30);
  while (rqProceed(q))
    if (candidateIsOpaque(q)) rqConfirm(q);
  uvec2 w = rqWork(q);
  work += w.x + w.y;
  return rqCommittedHit(q);
}

// Radiance arriving at `origin` from direction `dir`: shades the first hit and follows
// mirror bounces (up to `depth`) and thin transmissive walls (straight on, not counted as
// bounces: a thin glass shell has a front and a back wall), RB_RT_MAX_DEPTH events in all.
// `lobe`: the roughness of the surface the ray was reflected off (0 for a ray passed through
// or from a probe). One ray follows a glossy surface's mirror direction; where it leaves for
// the sky, the sky is read blurred for that roughness, as the hits' own environment
// reflections are (split-sum) and as the raster fallback reads it. Read sharp, a glossy
// model's sky reflection (the sun's a bright spot) was the tracer's alone: FLIP of `none`
// against `all` on Suzanne 0.0357 / 0.0132, 0.0036 / 0.0032 with the lobe; ToyCar 0.0505 /
// 0.0650, 0.0212 / 0.0386; the WaterBottle 0.0186 / 0.0218, 0.0015 / 0.0013.
vec3 traceRadiance(vec3 origin, vec3 dir, float lobe, uint depth, inout uint work) {
  vec3 throughput = vec3(1.0), result = vec3(0.0);
  uint bounces = 0u;
  for (int event = 0; event < 2 * RB_RT_MAX_DEPTH; ++event) {
    RayQuery q;
    if (!traceClosest(origin, dir, q, work)) return result + throughput * prefiltered(dir, lobe);
    HitSurface h = hitSurface(rqCommittedObject(q), rqCommittedPrimitive(q), rqCommittedBarycentrics(q), rqCommittedMaterial(q), dir);
    uint flags = floatBitsToUint(materials[h.material].normalScaleThicknessFlags.z);
    if (event == 0) {
      rbFirstHitInside = !h.frontFace && (flags & RB_MATERIAL_DOUBLE_SIDED) == 0u;
      rbFirstHitDistance = rqCommittedT(q) * length(dir);
    }
    vec3 V = -dir;
    result += throughput * shadeHit(h, V, work);
    vec3 weight, transmitWeight;
    layeredEnvWeights(h.baseColor.rgb, h.metallic, h.roughness, h.transmission, h.layers, h.normal, V, weight, transmitWeight);
    vec3 R = reflect(dir, h.normal);
    float transmission = h.transmission * (1.0 - h.metallic);
    bool thinWall = transmission > 0.0 && materials[h.material].normalScaleThicknessFlags.y <= 0.0;
    if (thinWall) {
      // The wall's reflection from the environment; the ray goes on through it.
      result += throughput * prefiltered(R, h.roughness) * weight;
      throughput *= transmitWeight;
      origin = offsetRay(h.position, -h.geometricNormal);
      continue;
    }
    if (bounces + 1u < depth && h.roughness <= maxTracedRoughness()) {
      ++bounces;
      throughput *= weight;
      origin = offsetRay(h.position, h.geometricNormal);
      dir = R;
      lobe = h.roughness;
      continue;
    }
    // Last bounce: the hit's own specular reflection (and, for a volume, what it transmits)
    // comes from the environment.
    result += throughput * prefiltered(R, h.roughness) * weight;
    if (transmission > 0.0) result += throughput * prefiltered(dir, h.roughness) * transmitWeight;
    return result;
  }
  return result;
}

#endif
