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

}  // namespace raybudget::select
