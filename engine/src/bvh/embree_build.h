// A thin RAII layer over Embree's BVH builder (rtcBuildBVH, binned SAH, optional spatial
// splits): builds a binary tree over boxes in Embree's own allocator and flattens it into
// our GPU node layout.
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

// A primitive reference for the build: a box and the ID its leaf reports. Several references
// may share an ID (a split triangle).
struct BuildRef {
  Box box;
  uint32_t id;
};

// What the builder aims for: depth and leaf size limits, and the SAH's cost of testing one
// primitive relative to visiting one node.
struct TreeShape {
  uint32_t maxDepth;
  uint32_t maxLeafSize;
  float intersectionCost = 1.0f;
};

struct FlatTree {
  uint32_t root = 0;
  uint32_t nodeCount = 0;
  float sahCost = 0.0f;  // with node and primitive costs 1, whatever the shape asked for
};

// Splits primitive `id`, whose reference currently has box `clip`, at x[axis] == position into
// the boxes of its parts on either side (bvh/spatial_split.h).
using SplitFunction = std::function<void(uint32_t id, const Box& clip, int axis, float position, Box& left, Box& right)>;

// Builds an SAH BVH2 over `refs` and appends its nodes to `nodes`. Each leaf's IDs go to
// `emitLeaf`, which stores them in the order it likes and returns the absolute index of the
// first one. Leaves hold at most `shape.maxLeafSize` references (more only where the depth
// limit forces it). With `split`, the builder may also split references spatially: an ID
// may then appear in several leaves. Throws raybudget::Error.
FlatTree buildTree(const std::vector<BuildRef>& refs, const TreeShape& shape, std::vector<gpu::GpuBvhNode>& nodes,
                   const std::function<uint32_t(const uint32_t* ids, uint32_t count)>& emitLeaf, const SplitFunction& split = {});

// The smallest float box containing `b` after rounding outwards by one ulp per side.
Box roundOutwards(const Box& b);

}  // namespace raybudget::bvh
