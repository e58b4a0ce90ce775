#include "select/object_params.h"

#include <algorithm>

#include "shared/selection.h"

namespace raybudget::select {

ObjectParams objectParams(const Scene& scene, const Object& object, float maxRoughness) {
  bool reflective = false, transmissive = false;
  for (const Primitive& p : scene.meshes[object.mesh].primitives) {
    const Material& m = scene.materials[size_t(p.material)];
    reflective = reflective || (m.metallic >= 0.5f && m.roughness <= maxRoughness);
    transmissive = transmissive || m.transmission > 0.0f;
  }
  const float derivedQ = float(scene.lights.size()) + (reflective ? 1.0f : 0.0f) + (transmissive ? 2.0f : 0.0f);
  ObjectParams p;
  p.K = object.params.importanceK.value_or(kDefaultK);
  p.Q = object.params.raysQ.value_or(derivedQ);
  p.I = object.params.hysteresisI.value_or(kDefaultI);
  return p;
}

glm::vec3 itemPriors(const Scene& scene, const Object& object) {
  float reflected = 0.0f, transmitted = 0.0f;
  for (const Primitive& p : scene.meshes[object.mesh].primitives) {
    const Material& m = scene.materials[size_t(p.material)];
    const float r = (m.ior - 1.0f) / (m.ior + 1.0f);
    const glm::vec3 base(m.baseColorFactor);
    const float luminance = glm::dot(base, glm::vec3(0.2126f, 0.7152f, 0.0722f));
    const float f0 = std::clamp((1.0f - m.metallic) * r * r + m.metallic * luminance, 0.0f, 1.0f);
    const float fresnel = f0 + (1.0f - f0) / 21.0f;
    reflected = std::max(reflected, fresnel);
    transmitted = std::max(transmitted, std::clamp(m.transmission * (1.0f - m.metallic), 0.0f, 1.0f) * (1.0f - fresnel));
  }
  return {float(RB_PRIOR_BENEFIT_SHADOWS), float(RB_PRIOR_BENEFIT_REFLECTIONS) * reflected, float(RB_PRIOR_BENEFIT_REFRACTIONS) * transmitted};
}

}  // namespace raybudget::select
