// Our compute BVH on the device, as shaders/include/rayquery_compute.glsl reads it: nodes
// and triangles in RGBA32UI uniform texel buffers, instances in a storage buffer.
#pragma once
#include "bvh/scene_bvh.h"
#include "vk/context.h"
#include "vk/resources.h"

namespace raybudget::passes {

struct BvhBuffers {
  vk::Buffer nodes;
  vk::Buffer triangles;
  vk::Buffer instances;
  vk::Owned<VkBufferView> nodeTexels, triangleTexels;
  size_t bytes() const { return size_t(nodes.size + triangles.size + instances.size); }
};

// `updatable`: nodes and instances can be copied into (TLAS rebuilds for moved objects).
BvhBuffers uploadBvh(const vk::Context& ctx, const bvh::SceneBvh& bvh, bool updatable);

}  // namespace raybudget::passes
