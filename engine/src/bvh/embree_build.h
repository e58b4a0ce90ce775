// A thin RAII layer over Embree's BVH builder (rtcBuildBVH, binned SAH): builds a binary
// tree over boxes in Embree's own allocator and flattens it into our GPU node layout.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "shared/bvh.h"

namespace raybudget::bvh {

struct Box {
  glm::vec3 min;
  glm::vec3 max;
};

struct FlatTree {
  uint32_t root = 0;
  uint32_t nodeCount = 0;
  float sahCost = 0.0f;
};

// Builds an SAH BVH2 over `boxes` and appends its nodes to `nodes`. Each leaf's primitive
// IDs (indices into `boxes`) go to `emitLeaf`, which stores them in the order it likes and
// returns the absolute index of the first one. Leaves hold at most `maxLeafSize` primitives
// (more only where the depth limit forces it). Throws raybudget::Error.
FlatTree buildTree(const std::vector<Box>& boxes, uint32_t maxDepth, uint32_t maxLeafSize, std::vector<gpu::GpuBvhNode>& nodes,
                   const std::function<uint32_t(const uint32_t* ids, uint32_t count)>& emitLeaf);

// The smallest float box containing `b` after rounding outwards by one ulp per side.
Box roundOutwards(const Box& b);

}  // namespace raybudget::bvh
