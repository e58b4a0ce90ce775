// GGX prefiltering of a radiance cube (Karis 2013 split sum) for roughness level `mip` of
// RB_ENV_MIPS, roughness = mip / (mips - 1): the sky (env_prefilter.comp) and the reflection
// probes (probe_prefilter.comp) alike. Filtered importance sampling (Krivanek & Colbert 2008):
// each sample reads the source mip whose texel matches the sample's solid angle, which keeps
// 64 samples free of fireflies around the sun. The includer defines
// RB_PREFILTER_SOURCE(dir, lod), the source's radiance (RB_ENV_SIZE texels per side at lod 0).
#ifndef RB_PREFILTER_GLSL
#define RB_PREFILTER_GLSL

vec2 hammersley(uint i, uint n) {
  uint b = bitfieldReverse(i);
  return vec2(float(i) / float(n), float(b) * 2.3283064365386963e-10);
}

vec3 prefilterTexel(vec3 N, uint mip) {
  if (mip == 0u) return RB_PREFILTER_SOURCE(N, 0.0);
  float roughness = float(mip) / float(RB_ENV_MIPS - 1);
  float alpha = roughness * roughness;
  vec3 up = abs(N.y) < 0.999 ? vec3(0, 1, 0) : vec3(1, 0, 0);
  vec3 T = normalize(cross(up, N));
  vec3 B = cross(N, T);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  float texelSolidAngle = 4.0 * PI / (6.0 * float(RB_ENV_SIZE * RB_ENV_SIZE));
  for (uint i = 0u; i < RB_ENV_PREFILTER_SAMPLES; ++i) {
    vec2 xi = hammersley(i, RB_ENV_PREFILTER_SAMPLES);
    float phi = 2.0 * PI * xi.x;
    float cosTheta = sqrt((1.0 - xi.y) / (1.0 + (alpha * alpha - 1.0) * xi.y));
    float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
    vec3 H = T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta;
    vec3 L = reflect(-N, H);
    float NoL = dot(N, L);
    if (NoL <= 0.0) continue;
    // V = N: pdf(L) = D(H) / 4.
    float pdf = dGgx(cosTheta, max(alpha, 1e-3)) * 0.25;
    float sampleSolidAngle = 1.0 / (float(RB_ENV_PREFILTER_SAMPLES) * pdf + 1e-6);
    float lod = clamp(0.5 * log2(sampleSolidAngle / texelSolidAngle) + 1.0, 0.0, float(RB_ENV_MIPS - 1));
    sum += RB_PREFILTER_SOURCE(L, lod) * NoL;
    weight += NoL;
  }
  return sum / max(weight, 1e-6);
}

#endif
