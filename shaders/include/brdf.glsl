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

// Schlick's Fresnel towards f90; x^5 by multiplication (pow is exp2(log2) on software
// rasterisers).
vec3 fSchlick(vec3 f0, float f90, float VoH) {
  float x = 1.0 - clamp(VoH, 0.0, 1.0);
  float x2 = x * x;
  return f0 + (f90 - f0) * (x2 * x2 * x);
}

vec3 fSchlick(vec3 f0, float VoH) { return fSchlick(f0, 1.0, VoH); }

// F0 of a dielectric of the given IOR against air.
float f0FromIor(float ior) {
  float r = (ior - 1.0) / (ior + 1.0);
  return r * r;
}

float maxOf(vec3 v) { return max(v.x, max(v.y, v.z)); }

// What a material puts over or into its metallic-roughness base: KHR_materials_clearcoat (a
// dielectric coat, F0 0.04, with its own roughness and normal), KHR_materials_sheen (a fabric
// layer) and KHR_materials_specular (the dielectric reflection's strength and F0 colour).
struct Layers {
  float clearcoat;
  float clearcoatRoughness;
  vec3 clearcoatNormal;
  vec3 sheenColor;
  float sheenRoughness;
  float specular;   // the dielectric reflection's strength (its F90)
  vec3 specularF0;  // the dielectric F0 colour, before `specular`
};

Layers noLayers(vec3 N, float ior) {
  return Layers(0.0, 0.0, N, vec3(0.0), 0.0, 1.0, vec3(f0FromIor(ior)));
}

vec3 surfaceF0(vec3 baseColor, float metallic, Layers l) { return mix(l.specularF0 * l.specular, baseColor, metallic); }
float surfaceF90(float metallic, Layers l) { return mix(l.specular, 1.0, metallic); }

// The sheen's distribution (Estevez & Kulla 2017, "Production Friendly Microfacet Sheen
// BRDF"; alpha = roughness^2 as KHR_materials_sheen says) and Neubelt & Pettineo's visibility.
float dCharlie(float NoH, float roughness) {
  float invAlpha = 1.0 / max(roughness * roughness, 1e-3);
  float sin2h = max(1.0 - NoH * NoH, 0.0078125);  // Filament's floor: no pow(0, x) at NoH = 1
  return (2.0 + invAlpha) * pow(sin2h, invAlpha * 0.5) / (2.0 * PI);
}

float vNeubelt(float NoV, float NoL) { return clamp(1.0 / (4.0 * (NoL + NoV - NoL * NoV)), 0.0, 1.0); }

// The energy the sheen takes from the layers below it: three.js's constant fit of the sheen's
// directional albedo (1 - 0.157 max(sheen colour)).
float sheenScaling(Layers l) { return 1.0 - 0.157 * maxOf(l.sheenColor); }

// What the coat lets through to the layers below, seen along V (its Fresnel at its own normal).
float coatTransmittance(Layers l, vec3 V) {
  if (l.clearcoat <= 0.0) return 1.0;
  float NoV = clamp(dot(l.clearcoatNormal, V), 1e-4, 1.0);
  return 1.0 - l.clearcoat * fSchlick(vec3(0.04), NoV).x;
}

// The share of the base's light (diffuse, specular, transmitted) that leaves through the layers.
float layerAttenuation(Layers l, vec3 V) { return sheenScaling(l) * coatTransmittance(l, V); }

// Radiance reflected towards V from light arriving along L with irradiance E (NoL applied):
// the GGX/Smith base, the sheen over it, the coat over both (glTF's layering: each layer
// mixes the one below by its Fresnel or albedo).
vec3 shadeLayered(vec3 N, vec3 V, vec3 L, vec3 baseColor, float metallic, float roughness, float transmission, Layers l) {
  vec3 H = normalize(V + L);
  float NoL = clamp(dot(N, L), 0.0, 1.0);
  float NoV = clamp(abs(dot(N, V)), 1e-4, 1.0);
  float NoH = clamp(dot(N, H), 0.0, 1.0);
  float VoH = dot(V, H);
  float alpha = max(roughness * roughness, 0.002);
  vec3 F = fSchlick(surfaceF0(baseColor, metallic, l), surfaceF90(metallic, l), VoH);
  vec3 specular = F * dGgx(NoH, alpha) * vSmithGgx(NoV, NoL, alpha);
  vec3 diffuse = (1.0 - F) * (1.0 - metallic) * (1.0 - transmission) * baseColor / PI;
  vec3 color = (diffuse + specular) * NoL;
  if (maxOf(l.sheenColor) > 0.0) color = color * sheenScaling(l) + l.sheenColor * dCharlie(NoH, l.sheenRoughness) * vNeubelt(NoV, NoL) * NoL;
  if (l.clearcoat > 0.0) {
    vec3 Nc = l.clearcoatNormal;
    float cNoL = clamp(dot(Nc, L), 0.0, 1.0);
    float cNoV = clamp(abs(dot(Nc, V)), 1e-4, 1.0);
    float cAlpha = max(l.clearcoatRoughness * l.clearcoatRoughness, 0.002);
    float Fc = l.clearcoat * fSchlick(vec3(0.04), VoH).x;
    color = color * (1.0 - Fc) + Fc * dGgx(clamp(dot(Nc, H), 0.0, 1.0), cAlpha) * vSmithGgx(cNoV, cNoL, cAlpha) * cNoL;
  }
  return color;
}

// Analytic fit of the split-sum environment BRDF (Karis 2014, "Physically Based Shading on
// Mobile"): scale and bias of F0 without a lookup texture.
vec3 envBrdfApprox(vec3 f0, float f90, float roughness, float NoV) {
  const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
  const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 r = roughness * c0 + c1;
  float a004 = min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
  vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
  return f0 * ab.x + f90 * ab.y;
}

vec3 envBrdfApprox(vec3 f0, float roughness, float NoV) { return envBrdfApprox(f0, 1.0, roughness, NoV); }

// The split-sum weights of a surface's environment light: its base's reflection and what it
// transmits (both through its layers).
void layeredEnvWeights(vec3 baseColor, float metallic, float roughness, float transmission, Layers l, vec3 N, vec3 V,
                       out vec3 reflectWeight, out vec3 transmitWeight) {
  float NoV = clamp(dot(N, V), 1e-4, 1.0);
  vec3 brdf = envBrdfApprox(surfaceF0(baseColor, metallic, l), surfaceF90(metallic, l), roughness, NoV);
  float through = layerAttenuation(l, V);
  reflectWeight = brdf * through;
  transmitWeight = baseColor * transmission * (1.0 - metallic) * (vec3(1.0) - brdf) * through;
}

// The sheen's response to the environment (three.js's fit of its directional albedo, DG).
float iblSheen(float NoV, float roughness) {
  float r2 = roughness * roughness;
  float a = roughness < 0.25 ? -339.2 * r2 + 161.4 * roughness - 25.9 : -8.48 * r2 + 14.3 * roughness - 9.95;
  float b = roughness < 0.25 ? 44.0 * r2 - 23.7 * roughness + 3.26 : 1.97 * r2 - 3.27 * roughness + 0.72;
  return clamp(exp(a * NoV + b) + (roughness < 0.25 ? 0.0 : 0.1 * (roughness - 0.25)), 0.0, PI);
}

// The diffuse base, the sheen and the coat under environment light: the base and the sheen lit
// by `irradiance` (the environment's irradiance / pi at N), the coat reflecting `coatRadiance`
// (the prefiltered surroundings along the coat's mirror direction at its roughness). The base's
// specular reflection and transmission are the fallback's or the tracer's (layeredEnvWeights).
vec3 ambientLight(vec3 baseColor, float metallic, float transmission, Layers l, vec3 N, vec3 V, vec3 irradiance, vec3 coatRadiance) {
  vec3 c = irradiance * baseColor * (1.0 - metallic) * (1.0 - transmission) * layerAttenuation(l, V);
  if (maxOf(l.sheenColor) > 0.0) c += irradiance * l.sheenColor * iblSheen(clamp(dot(N, V), 0.0, 1.0), l.sheenRoughness);
  if (l.clearcoat > 0.0)
    c += coatRadiance * l.clearcoat * envBrdfApprox(vec3(0.04), l.clearcoatRoughness, clamp(dot(l.clearcoatNormal, V), 1e-4, 1.0));
  return c;
}

// The coat's mirror direction (for ambientLight's coatRadiance).
vec3 coatReflection(Layers l, vec3 V) { return reflect(-V, l.clearcoatNormal); }

#endif
