#include "scene/mesh_builder.h"

#include <cmath>

#include <tiny_gltf.h>

#include "raybudget/error.h"
#include "scene/accessor_reader.h"
#include "scene/gltf_rules.h"
#include "scene/triangles.h"

namespace raybudget::gltf {
namespace {

bool finite3(const glm::vec4& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Triangle list from the primitive's indices (or 0..n-1), converting strips and fans.
std::vector<uint32_t> triangleList(int mode, const std::vector<uint32_t>& idx) {
  std::vector<uint32_t> out;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    out.assign(idx.begin(), idx.begin() + std::ptrdiff_t(idx.size() / 3 * 3));
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 2; i < idx.size(); ++i) {
      // Odd triangles swap two vertices to keep a consistent winding.
      if (i % 2 == 0) out.insert(out.end(), {idx[i - 2], idx[i - 1], idx[i]});
      else out.insert(out.end(), {idx[i - 1], idx[i - 2], idx[i]});
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (size_t i = 2; i < idx.size(); ++i) out.insert(out.end(), {idx[0], idx[i - 1], idx[i]});
  }
  return out;
}

int defaultMaterial(Scene& scene) {
  for (size_t i = 0; i < scene.materials.size(); ++i)
    if (scene.materials[i].name == "raybudget-default") return int(i);
  Material m;
  m.name = "raybudget-default";
  m.metallic = 0.0f;
  m.roughness = 0.6f;
  scene.materials.push_back(m);
  return int(scene.materials.size() - 1);
}

}  // namespace

Mesh buildMesh(const tinygltf::Model& model, int meshIndex, const std::string& where, Scene& scene) {
  const tinygltf::Mesh& gm = model.meshes[size_t(meshIndex)];
  Mesh mesh;
  mesh.name = gm.name.empty() ? "mesh" + std::to_string(meshIndex) : gm.name;
  for (size_t p = 0; p < gm.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = gm.primitives[p];
    const std::string at = where + ": mesh " + std::to_string(meshIndex) + " ('" + mesh.name + "') primitive " +
                           std::to_string(p);
    if (prim.mode < TINYGLTF_MODE_TRIANGLES && prim.mode >= 0) {
      ++scene.stats.skippedPointLinePrimitives;
      scene.warnings.push_back(at + ": points/lines primitive skipped");
      continue;
    }
    if (prim.mode > TINYGLTF_MODE_TRIANGLE_FAN) throw Error(at + ": unknown primitive mode " + std::to_string(prim.mode));
    checkPrimitiveFormats(model, prim, at);
    const auto posIt = prim.attributes.find("POSITION");
    if (posIt == prim.attributes.end()) throw Error(at + ": has no POSITION attribute");
    const std::vector<glm::vec4> pos = readVec4(model, posIt->second, at + " POSITION");
    for (size_t i = 0; i < pos.size(); ++i)
      if (!finite3(pos[i]))
        throw Error(at + ": POSITION of vertex " + std::to_string(i) + " is not finite (NaN or Inf)");
    checkPositionBounds(model, posIt->second, pos, at, scene.warnings);

    // `repairable`: non-finite values are left for the caller to repair (normals), else refused.
    auto optional = [&](const char* name, glm::vec4 fill, bool repairable = false) {
      const auto it = prim.attributes.find(name);
      std::vector<glm::vec4> v;
      if (it != prim.attributes.end()) {
        v = readVec4(model, it->second, at + " " + name, fill);
        if (v.size() != pos.size())
          throw Error(at + ": " + name + " has " + std::to_string(v.size()) + " elements but POSITION has " +
                      std::to_string(pos.size()));
        for (size_t i = 0; i < v.size() && !repairable; ++i)
          if (!finite3(v[i])) throw Error(at + ": " + name + " of vertex " + std::to_string(i) + " is not finite");
      }
      return v;
    };
    const std::vector<glm::vec4> nrm = optional("NORMAL", glm::vec4(0, 0, 1, 0), true);
    const std::vector<glm::vec4> uv = optional("TEXCOORD_0", glm::vec4(0, 0, 0, 0));
    const std::vector<glm::vec4> col = optional("COLOR_0", glm::vec4(1.0f));

    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
      idx = readIndices(model, prim.indices, at + " indices");
      for (size_t i = 0; i < idx.size(); ++i)
        if (idx[i] >= pos.size())
          throw Error(at + ": index " + std::to_string(i) + " is " + std::to_string(idx[i]) +
                      ", out of range for " + std::to_string(pos.size()) + " vertices");
    } else {
      idx.resize(pos.size());
      for (size_t i = 0; i < idx.size(); ++i) idx[i] = uint32_t(i);
    }
    std::vector<uint32_t> tris = triangleList(prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode, idx);

    // Drop zero-area triangles: they add BVH and raster work and no pixels.
    std::vector<glm::vec3> pos3(pos.size());
    for (size_t i = 0; i < pos.size(); ++i) pos3[i] = glm::vec3(pos[i]);
    size_t dropped = 0;
    const std::vector<uint32_t> kept = dropZeroAreaTriangles(pos3, tris, dropped);
    if (dropped > 0) {
      scene.stats.droppedDegenerateTriangles += dropped;
      scene.warnings.push_back(at + ": dropped " + std::to_string(dropped) + " zero-area triangles");
    }
    if (kept.empty()) continue;

    // Area-weighted normals where the file has none, and in place of its NaN, Inf or zero ones
    // (as three.js and Blender do), with a warning.
    auto unusable = [&](size_t i) { return nrm.empty() || !finite3(nrm[i]) || glm::vec3(nrm[i]) == glm::vec3(0.0f); };
    size_t badNormals = 0;
    for (size_t i = 0; i < nrm.size(); ++i) badNormals += unusable(i);
    const std::vector<glm::vec3> generated = nrm.empty() || badNormals ? areaWeightedNormals(pos3, kept) : std::vector<glm::vec3>{};
    if (badNormals)
      scene.warnings.push_back(at + ": " + std::to_string(badNormals) + " NORMAL values are NaN, infinite or zero; recomputed from the geometry");

    const uint32_t base = uint32_t(mesh.vertices.size());
    for (size_t i = 0; i < pos.size(); ++i) {
      Vertex v;
      v.position = glm::vec3(pos[i]);
      glm::vec3 n = unusable(i) ? generated[i] : glm::vec3(nrm[i]);
      const float len = glm::length(n);
      v.normal = len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
      if (!uv.empty()) v.uv = glm::vec2(uv[i]);
      if (!col.empty()) v.color = col[i];
      mesh.vertices.push_back(v);
    }
    Primitive out;
    out.firstIndex = uint32_t(mesh.indices.size());
    out.indexCount = uint32_t(kept.size());
    if (prim.material >= int(model.materials.size()))
      throw Error(at + ": material " + std::to_string(prim.material) + " does not exist");
    out.material = prim.material >= 0 ? prim.material : defaultMaterial(scene);
    for (uint32_t i : kept) mesh.indices.push_back(base + i);
    mesh.primitives.push_back(out);
  }
  if (!mesh.indices.empty()) {
    mesh.boundsMin = mesh.boundsMax = mesh.vertices[mesh.indices[0]].position;
    for (uint32_t i : mesh.indices) {
      mesh.boundsMin = glm::min(mesh.boundsMin, mesh.vertices[i].position);
      mesh.boundsMax = glm::max(mesh.boundsMax, mesh.vertices[i].position);
    }
  }
  return mesh;
}

}  // namespace raybudget::gltf
