// A loaded scene rebuilt through raybudget::SceneBuilder, the way a host engine hands over
// its own arrays: positions and normals read from the interleaved Vertex array (stride
// sizeof(Vertex)), one material per instance, the lights and camera copied.
#pragma once
#include "raybudget/scene_builder.h"

namespace raybudget::test {

inline Scene rebuiltThroughBuilder(const Scene& loaded) {
  SceneBuilder b;
  for (const Material& m : loaded.materials) {
    MaterialHints h;
    h.name = m.name;
    h.baseColor = m.baseColorFactor;
    h.metallic = m.metallic;
    h.roughness = m.roughness;
    h.transmission = m.transmission;
    h.ior = m.ior;
    h.thickness = m.thickness;
    h.attenuationDistance = m.attenuationDistance;
    h.attenuationColor = m.attenuationColor;
    h.emissive = m.emissive;
    h.unlit = m.unlit;
    h.doubleSided = m.doubleSided;
    b.addMaterial(h);
  }
  for (const Mesh& m : loaded.meshes) {
    MeshInput in;
    in.name = m.name;
    in.vertexCount = m.vertices.size();
    in.positions = {&m.vertices[0].position, sizeof(Vertex)};
    in.normals = {&m.vertices[0].normal, sizeof(Vertex)};
    in.indices = m.indices;
    b.addMesh(in);
  }
  for (const Object& o : loaded.objects)
    b.addInstance(o.mesh, uint32_t(loaded.meshes[o.mesh].primitives[0].material), o.transform, o.params, o.name);
  for (const Light& l : loaded.lights) b.addLight(l);
  if (loaded.camera) b.setCamera(*loaded.camera);
  return b.build();
}

}  // namespace raybudget::test
