#include "select/object_params.h"

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

}  // namespace raybudget::select
