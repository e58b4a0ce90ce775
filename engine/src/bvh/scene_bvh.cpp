#include "bvh/scene_bvh.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <unordered_map>

#include "bvh/embree_build.h"
#include "bvh/spatial_split.h"
#include "raybudget/error.h"

namespace raybudget::bvh {
namespace {

// Depth limits keep the two-level traversal within RB_BVH_STACK_SIZE entries: a stack
// holds at most one entry per level, plus one marker between the levels.
constexpr uint32_t kBlasMaxDepth = 38;
constexpr uint32_t kTlasMaxDepth = 24;
static_assert(kBlasMaxDepth + kTlasMaxDepth + 1 <= RB_BVH_STACK_SIZE);
// A triangle test in a leaf costs about half a node visit on lavapipe (three texel fetches in
// a tight loop against four plus two slab tests and a stack push): with 0.5 the SAH builds
// somewhat larger leaves and fewer nodes, measured +1-8% on court, ToyCar and
// MetalRoughSpheres (docs/TRACER.md). TLAS leaves are single instances.
constexpr TreeShape kBlasShape{kBlasMaxDepth, RB_BVH_MAX_LEAF_SIZE, 0.5f};
constexpr TreeShape kTlasShape{kTlasMaxDepth, 1, 1.0f};
static_assert(sizeof(gpu::GpuBvhNode) == 64 && sizeof(gpu::GpuTriangle) == 48 && sizeof(gpu::GpuInstance) == 64);

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// True when a few triangles are much larger than the typical one: the mean box surface area
// is at least twice the median. Evenly tessellated meshes (spheres, grids, scans) stay well
// below; they gain nothing from spatial splits (measured: docs/TRACER.md).
bool unevenTriangleSizes(const std::vector<BuildRef>& refs) {
  std::vector<float> area(refs.size());
  double sum = 0.0;
  for (size_t i = 0; i < refs.size(); ++i) {
    const glm::vec3 d = refs[i].box.max - refs[i].box.min;
    area[i] = d.x * d.y + d.y * d.z + d.z * d.x;
    sum += double(area[i]);
  }
  std::nth_element(area.begin(), area.begin() + std::ptrdiff_t(area.size() / 2), area.end());
  return sum / double(area.size()) >= 2.0 * double(area[area.size() / 2]);
}

// What a mesh's BLAS stores per triangle besides the vertices: the material field (relative
// to the instance's material base) and the flags.
struct TriangleFields {
  std::vector<uint32_t> material, flags;
  uint32_t materialBase = 0;  // goes into each instance of the mesh
};

TriangleFields triangleFields(const Scene& scene, const Mesh& mesh) {
  const size_t triCount = mesh.indices.size() / 3;
  TriangleFields f;
  f.material.assign(triCount, 0u);
  f.flags.assign(triCount, 0u);
  // One material: it goes to the instance, so meshes differing only in it share a BLAS.
  const bool oneMaterial = mesh.primitives.size() == 1;
  if (oneMaterial) f.materialBase = uint32_t(mesh.primitives[0].material);
  for (const Primitive& p : mesh.primitives) {
    const Material& m = scene.materials[size_t(p.material)];
    for (uint32_t t = p.firstIndex / 3; t < (p.firstIndex + p.indexCount) / 3; ++t) {
      f.material[t] = oneMaterial ? 0u : uint32_t(p.material);
      f.flags[t] = m.alphaMode == AlphaMode::Mask ? 0u : RB_TRIANGLE_OPAQUE;
    }
  }
  return f;
}

glm::vec3 vertexOf(const Mesh& mesh, size_t triangle, int k) { return mesh.vertices[mesh.indices[triangle * 3 + size_t(k)]].position; }

// Same triangles (positions, in order) and the same per-triangle fields: one BLAS serves both.
bool sameBlas(const Mesh& a, const TriangleFields& fa, const Mesh& b, const TriangleFields& fb) {
  if (a.indices.size() != b.indices.size() || fa.material != fb.material || fa.flags != fb.flags) return false;
  for (size_t t = 0; t < a.indices.size() / 3; ++t)
    for (int k = 0; k < 3; ++k)
      if (vertexOf(a, t, k) != vertexOf(b, t, k)) return false;
  return true;
}

uint64_t blasHash(const Mesh& mesh, const TriangleFields& f) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a over the positions' bits and the fields
  auto mix = [&](uint32_t v) { h = (h ^ v) * 1099511628211ull; };
  for (size_t t = 0; t < mesh.indices.size() / 3; ++t) {
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) mix(std::bit_cast<uint32_t>(vertexOf(mesh, t, k)[c]));
    mix(f.material[t]);
    mix(f.flags[t]);
  }
  return h;
}

BlasInfo buildBlas(const Scene& scene, const Mesh& mesh, const TriangleFields& fields, SpatialSplits splits, SceneBvh& out) {
  const size_t triCount = mesh.indices.size() / 3;
  auto vertex = [&](size_t t, int k) { return vertexOf(mesh, t, k); };
  std::vector<BuildRef> refs(triCount);
  for (size_t t = 0; t < triCount; ++t) {
    const glm::vec3 a = vertex(t, 0), b = vertex(t, 1), c = vertex(t, 2);
    refs[t] = {{glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c))}, uint32_t(t)};
  }
  BlasInfo info;
  info.firstTriangle = uint32_t(out.triangles.size());
  info.triangleCount = uint32_t(triCount);
  info.materialBase = fields.materialBase;
  if (triCount == 0) return info;  // every triangle was degenerate: no object uses this mesh
  info.spatialSplits = splits == SpatialSplits::Always || (splits == SpatialSplits::Auto && unevenTriangleSizes(refs));
  const SplitFunction split = [&](uint32_t t, const Box& clip, int axis, float position, Box& left, Box& right) {
    const glm::vec3 v[3] = {vertex(t, 0), vertex(t, 1), vertex(t, 2)};
    splitTriangleBox(v, clip, axis, position, left, right);
  };
  const FlatTree tree = buildTree(refs, kBlasShape, out.nodes, [&](const uint32_t* ids, uint32_t count) {
    const uint32_t first = uint32_t(out.triangles.size());
    // The traversal packs a BLAS leaf into one stack entry: 28 bits of index, 3 of count.
    if (count > 8 || first + count >= (1u << 28))
      throw Error(scene.path.string() + ": mesh '" + mesh.name + "' gives a BVH leaf the traversal cannot encode (" + std::to_string(count) +
                  " triangles from " + std::to_string(first) + ")");
    for (uint32_t i = 0; i < count; ++i) {
      const uint32_t t = ids[i];
      gpu::GpuTriangle tri;
      tri.v0Primitive = glm::vec4(vertex(t, 0), std::bit_cast<float>(t));
      tri.v1Material = glm::vec4(vertex(t, 1), std::bit_cast<float>(fields.material[t]));
      tri.v2Flags = glm::vec4(vertex(t, 2), std::bit_cast<float>(fields.flags[t]));
      out.triangles.push_back(tri);
    }
    return first;
  }, info.spatialSplits ? split : SplitFunction{});
  info.references = uint32_t(out.triangles.size()) - info.firstTriangle;
  info.root = tree.root;
  info.nodeCount = tree.nodeCount;
  info.sahCost = tree.sahCost;
  return info;
}

}  // namespace

void rebuildTlas(SceneBvh& bvh, std::span<const Object> objects) {
  const auto start = std::chrono::steady_clock::now();
  // The TLAS always sits after the BLAS nodes: drop the old one.
  bvh.nodes.resize(bvh.tlasNodeCount > 0 ? bvh.tlasRoot : bvh.nodes.size());
  bvh.instances.clear();
  std::vector<BuildRef> refs;
  for (const Object& o : objects) refs.push_back({{o.boundsMin, o.boundsMax}, uint32_t(refs.size())});
  const FlatTree tree = buildTree(refs, kTlasShape, bvh.nodes, [&](const uint32_t* ids, uint32_t count) {
    const uint32_t first = uint32_t(bvh.instances.size());
    for (uint32_t i = 0; i < count; ++i) {
      const Object& o = objects[ids[i]];
      const glm::mat4 inv = glm::inverse(o.transform);
      gpu::GpuInstance inst;
      for (int r = 0; r < 3; ++r) inst.worldToObject[r] = glm::vec4(inv[0][r], inv[1][r], inv[2][r], inv[3][r]);
      inst.blasObjectMask = glm::uvec4(bvh.blas[o.mesh].root, o.id, 0xFFu, bvh.blas[o.mesh].materialBase);
      bvh.instances.push_back(inst);
    }
    return first;
  });
  bvh.tlasRoot = tree.root;
  bvh.tlasNodeCount = tree.nodeCount;
  bvh.nodes[RB_BVH_TLAS_ROOT_NODE] = bvh.nodes[tree.root];
  bvh.tlasSahCost = tree.sahCost;
  bvh.stats.tlasMs = msSince(start);
  bvh.stats.nodes = bvh.nodes.size();
}

SceneBvh buildSceneBvh(const Scene& scene, const BuildOptions& options) {
  SceneBvh bvh;
  bvh.nodes.push_back({});  // node 0: the TLAS root's copy, filled by rebuildTlas
  const auto start = std::chrono::steady_clock::now();
  // Meshes with the same triangles and fields (typically copies differing in material) share
  // the first one's BLAS.
  std::unordered_map<uint64_t, std::vector<uint32_t>> built;  // hash -> meshes with a BLAS of their own
  std::vector<TriangleFields> fields;
  for (const Mesh& m : scene.meshes) fields.push_back(triangleFields(scene, m));
  for (uint32_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    std::vector<uint32_t>& same = built[blasHash(m, fields[i])];
    const auto owner = std::find_if(same.begin(), same.end(), [&](uint32_t j) { return sameBlas(scene.meshes[j], fields[j], m, fields[i]); });
    if (owner != same.end() && !m.indices.empty()) {
      BlasInfo shared = bvh.blas[*owner];
      shared.materialBase = fields[i].materialBase;
      shared.sharedWith = *owner;
      bvh.blas.push_back(shared);
      ++bvh.stats.sharedMeshes;
      continue;
    }
    same.push_back(i);
    bvh.blas.push_back(buildBlas(scene, m, fields[i], options.spatialSplits, bvh));
    bvh.stats.triangles += bvh.blas.back().triangleCount;
    bvh.stats.splitMeshes += bvh.blas.back().spatialSplits;
  }
  bvh.stats.blasMs = msSince(start);
  rebuildTlas(bvh, scene.objects);
  bvh.stats.references = bvh.triangles.size();
  bvh.stats.bytesPerTriangle = double(bvh.nodes.size() * sizeof(gpu::GpuBvhNode) + bvh.triangles.size() * sizeof(gpu::GpuTriangle)) /
                               double(std::max<size_t>(bvh.stats.triangles, 1));
  return bvh;
}

}  // namespace raybudget::bvh
