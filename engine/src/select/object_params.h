// K, Q and I of an object: authored in glTF extras.raybudget, else derived (DESIGN.md
// section 1): K = 1, I = 0.5, Q = the shadow rays (one per light) + 1 reflection ray for a
// smooth metallic or mirror-like material + 2 for a transmissive one (in and out).
#pragma once
#include "raybudget/scene.h"
#include "select/metrics.h"

namespace raybudget::select {

inline constexpr float kDefaultK = 1.0f;
inline constexpr float kDefaultI = 0.5f;

// `maxRoughness`: reflections are traced up to this roughness (RayTracingSettings).
ObjectParams objectParams(const Scene& scene, const Object& object, float maxRoughness);

// The prior benefit per covered pixel of the object's items (shadows, reflections,
// refractions: what `benefit` assumes before measuring an item and drifts back to while it is
// not traced), from its materials' factors, the most of its primitives (textures only lower
// a factor): reflections RB_PRIOR_BENEFIT_REFLECTIONS times the cosine-weighted mean of
// Schlick's Fresnel, F0 + (1 - F0) / 21, with F0 from the IOR for a dielectric and the base
// colour's luminance for a metal (a mirror keeps the whole prior, a smooth dielectric under a
// tenth of it); refractions RB_PRIOR_BENEFIT_REFRACTIONS times the share transmitted,
// transmission x (1 - metallic) x (1 - that Fresnel mean); shadows RB_PRIOR_BENEFIT_SHADOWS.
glm::vec3 itemPriors(const Scene& scene, const Object& object);

}  // namespace raybudget::select
