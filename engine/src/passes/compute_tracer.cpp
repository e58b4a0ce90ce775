// Our compute BVH as the scene's tracer: BLAS per mesh and a TLAS built on the CPU
// (bvh/scene_bvh.h), read by the shaders from two texel buffers and an instance buffer.
// Moved objects rebuild the TLAS on the CPU; the frame copies its nodes and instances.
#include <algorithm>
#include <chrono>
#include <vector>
#include <cstring>

#include "bvh/scene_bvh.h"
#include "passes/bindings.h"
#include "passes/bvh_buffers.h"
#include "passes/scene_tracer.h"
#include "probe_capture_comp.h"
#include "rt_effects_comp.h"
#include "rt_shadows_comp.h"
#include "shared/config.h"
#include "vk/check.h"

namespace raybudget::passes {
namespace {

class ComputeTracer final : public SceneTracer {
 public:
  ComputeTracer(const vk::Context& ctx, const Scene& scene, SpatialSplits splits) : ctx_(ctx), bvh_(bvh::buildSceneBvh(scene, {splits})) {
    buffers_ = uploadBvh(ctx, bvh_, true);
    stats_.buildMs = bvh_.stats.blasMs + bvh_.stats.tlasMs;
    stats_.triangles = bvh_.stats.triangles;
    stats_.references = bvh_.stats.references;
    stats_.splitMeshes = bvh_.stats.splitMeshes;
    stats_.sharedMeshes = bvh_.stats.sharedMeshes;
    stats_.bytes = buffers_.bytes();
    bvh_.triangles.clear();  // on the GPU now; TLAS rebuilds need only nodes and instances
    bvh_.triangles.shrink_to_fit();
  }

  Tracer kind() const override { return Tracer::Compute; }
  AccelStats stats() const override { return stats_; }
  vk::Spirv shader(TraceShader which) const override {
    switch (which) {
      case TraceShader::Shadows: return vk::Spirv(kSpirv_rt_shadows_comp);
      case TraceShader::Effects: return vk::Spirv(kSpirv_rt_effects_comp);
      case TraceShader::ReflectionProbe: break;
    }
    return vk::Spirv(kSpirv_probe_capture_comp);
  }

  void writeBindings(VkDevice device, VkDescriptorSet set, std::span<const uint32_t> only) const override {
    const VkBufferView texels[] = {buffers_.nodeTexels, buffers_.triangleTexels};
    const VkDescriptorBufferInfo instances{buffers_.instances.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w[3];
    for (uint32_t i = 0; i < 3; ++i) {
      w[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w[i].dstSet = set;
      w[i].dstBinding = kBvhNodes + i;
      w[i].descriptorCount = 1;
      w[i].descriptorType = i < 2 ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    }
    w[0].pTexelBufferView = &texels[0];
    w[1].pTexelBufferView = &texels[1];
    w[2].pBufferInfo = &instances;
    updateBindingsAmong(device, w, only);
  }

  double recordMovedObjects(VkCommandBuffer cmd, const Scene& shell, std::span<const gpu::GpuObject> records, vk::Buffer& staging,
                            const vk::Buffer& objectRecords) override {
    const auto start = std::chrono::steady_clock::now();
    bvh::rebuildTlas(bvh_, shell.objects);
    // The TLAS root's copy in node 0, the TLAS nodes, the instances, the object records.
    const VkDeviceSize nodeBytes = sizeof(gpu::GpuBvhNode), tlasBytes = bvh_.tlasNodeCount * nodeBytes;
    const VkDeviceSize instBytes = bvh_.instances.size() * sizeof(gpu::GpuInstance), objBytes = records.size_bytes();
    uint8_t* dst = stagingOf(ctx_, staging, nodeBytes + tlasBytes + instBytes + objBytes);
    std::memcpy(dst, &bvh_.nodes[RB_BVH_TLAS_ROOT_NODE], nodeBytes);
    std::memcpy(dst + nodeBytes, &bvh_.nodes[bvh_.tlasRoot], tlasBytes);
    std::memcpy(dst + nodeBytes + tlasBytes, bvh_.instances.data(), instBytes);
    std::memcpy(dst + nodeBytes + tlasBytes + instBytes, records.data(), objBytes);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const VkBufferCopy nodes[] = {{0, 0, nodeBytes}, {nodeBytes, bvh_.tlasRoot * nodeBytes, tlasBytes}};
    const VkBufferCopy instances{nodeBytes + tlasBytes, 0, instBytes}, objects{nodeBytes + tlasBytes + instBytes, 0, objBytes};
    vkCmdCopyBuffer(cmd, staging.buffer, buffers_.nodes.buffer, 2, nodes);
    vkCmdCopyBuffer(cmd, staging.buffer, buffers_.instances.buffer, 1, &instances);
    vkCmdCopyBuffer(cmd, staging.buffer, objectRecords.buffer, 1, &objects);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_MEMORY_READ_BIT);
    return ms;
  }

 private:
  const vk::Context& ctx_;
  bvh::SceneBvh bvh_;
  BvhBuffers buffers_;
  AccelStats stats_;
};

}  // namespace

std::unique_ptr<SceneTracer> createComputeTracer(const vk::Context& ctx, const Scene& scene, SpatialSplits splits) {
  return std::make_unique<ComputeTracer>(ctx, scene, splits);
}

}  // namespace raybudget::passes
