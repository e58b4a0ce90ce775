// The two-level BVH of a scene in the GPU layout of shaders/shared/bvh.h: one BLAS per mesh
// (meshes with the same triangles share one) built on the CPU with Embree's rtcBuildBVH
// (binned SAH, spatial splits where they pay), and a TLAS over the objects. Plain C++
// (Embree, no Vulkan).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "raybudget/bvh_options.h"
#include "raybudget/scene.h"
#include "shared/bvh.h"

namespace raybudget::bvh {

struct BuildOptions {
  SpatialSplits spatialSplits = SpatialSplits::Auto;
};

struct BlasInfo {
  uint32_t root = 0;           // node index
  uint32_t nodeCount = 0;
  uint32_t firstTriangle = 0;  // first leaf entry in SceneBvh::triangles
  uint32_t triangleCount = 0;  // the mesh's triangles
  uint32_t references = 0;     // leaf entries: more than triangleCount where triangles were split
  bool spatialSplits = false;  // built with spatial splits
  uint32_t materialBase = 0;   // this mesh's instances' material base (shaders/shared/bvh.h)
  int32_t sharedWith = -1;     // the mesh whose BLAS this one uses (same triangles), or -1
  float sahCost = 0.0f;        // SAH cost with traversal 1, intersection 1, relative to the root box
};

struct BuildStats {
  double blasMs = 0.0;  // all meshes
  double tlasMs = 0.0;
  size_t nodes = 0;
  size_t triangles = 0;           // triangles of the BLASes built (a shared BLAS counts once)
  size_t references = 0;          // leaf entries (SceneBvh::triangles): triangles plus split pieces
  size_t splitMeshes = 0;         // meshes built with spatial splits
  size_t sharedMeshes = 0;        // meshes that use another mesh's BLAS
  double bytesPerTriangle = 0.0;  // nodes + leaf entries per BLAS triangle (the instance array is per object)
};

struct SceneBvh {
  std::vector<gpu::GpuBvhNode> nodes;        // node 0 (TLAS root copy), every BLAS, then the TLAS
  std::vector<gpu::GpuTriangle> triangles;   // leaf order, per BLAS; a split triangle appears once per leaf it is in
  std::vector<gpu::GpuInstance> instances;   // TLAS leaf order
  std::vector<BlasInfo> blas;                // per mesh
  uint32_t tlasRoot = 0;
  uint32_t tlasNodeCount = 0;
  float tlasSahCost = 0.0f;
  BuildStats stats;
};

// Builds every BLAS and the TLAS. Objects get cull mask 0xFF.
SceneBvh buildSceneBvh(const Scene& scene, const BuildOptions& options = {});

// Rebuilds only the TLAS (objects moved; meshes unchanged), replacing the old TLAS nodes.
// The TLAS of N objects always has the same number of nodes, so its place in `nodes` stays.
void rebuildTlas(SceneBvh& bvh, std::span<const Object> objects);

}  // namespace raybudget::bvh
