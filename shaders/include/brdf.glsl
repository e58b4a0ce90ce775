// GGX / Smith microfacet BRDF (Walter et al. 2007; Karis 2013 "Real Shading in UE4").
#ifndef RB_BRDF_GLSL
#define RB_BRDF_GLSL

const float PI = 3.14159265359;

float dGgx(float NoH, float alpha) {
  float a2 = alpha * alpha;
  float d = NoH * NoH * (a2 - 1.0) + 1.0;
  return a2 / max(PI * d * d, 1e-8);
}

// Height-correlated Smith visibility V = G / (4 NoL NoV).
float vSmithGgx(float NoV, float NoL, float alpha) {
  float a2 = alpha * alpha;
  float gv = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
  float gl = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
  return 0.5 / max(gv + gl, 1e-8);
}

// Schlick's Fresnel; x^5 by multiplication (pow is exp2(log2) on software rasterisers).
vec3 fSchlick(vec3 f0, float VoH) {
  float x = 1.0 - clamp(VoH, 0.0, 1.0);
  float x2 = x * x;
  return f0 + (1.0 - f0) * (x2 * x2 * x);
}

// F0 of a dielectric of the given IOR against air.
float f0FromIor(float ior) {
  float r = (ior - 1.0) / (ior + 1.0);
  return r * r;
}

// Radiance reflected towards V from light arriving along L with irradiance E (NoL applied).
vec3 shadePbr(vec3 N, vec3 V, vec3 L, vec3 baseColor, float metallic, float roughness, float transmission, float ior) {
  vec3 H = normalize(V + L);
  float NoL = clamp(dot(N, L), 0.0, 1.0);
  float NoV = clamp(abs(dot(N, V)), 1e-4, 1.0);
  float NoH = clamp(dot(N, H), 0.0, 1.0);
  float alpha = max(roughness * roughness, 0.002);
  vec3 f0 = mix(vec3(f0FromIor(ior)), baseColor, metallic);
  vec3 F = fSchlick(f0, dot(V, H));
  vec3 specular = F * dGgx(NoH, alpha) * vSmithGgx(NoV, NoL, alpha);
  vec3 diffuse = (1.0 - F) * (1.0 - metallic) * (1.0 - transmission) * baseColor / PI;
  return (diffuse + specular) * NoL;
}

// Analytic fit of the split-sum environment BRDF (Karis 2014, "Physically Based Shading on
// Mobile"): scale and bias of F0 without a lookup texture.
vec3 envBrdfApprox(vec3 f0, float roughness, float NoV) {
  const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
  const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 r = roughness * c0 + c1;
  float a004 = min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
  vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
  return f0 * ab.x + ab.y;
}

#endif
