// The device's VK_KHR_ray_query acceleration structures as the scene's tracer
// (native_accel.h): the TLAS and the geometry table are what the shaders bind. Moved objects
// get new instance records and a TLAS rebuilt on the device within the frame.
#include <algorithm>
#include <chrono>
#include <vector>
#include <cstring>

#include "passes/bindings.h"
#include "passes/native_accel.h"
#include "passes/scene_tracer.h"
#include "probe_capture_comp_native.h"
#include "rt_effects_comp_native.h"
#include "rt_shadows_comp_native.h"
#include "vk/check.h"

namespace raybudget::passes {
namespace {

class NativeTracer final : public SceneTracer {
 public:
  NativeTracer(const vk::Context& ctx, const Scene& scene) : ctx_(ctx), accel_(ctx, scene) {
    for (const Mesh& m : scene.meshes) stats_.triangles += m.indices.size() / 3;
    stats_.buildMs = accel_.buildMs();
    stats_.references = stats_.triangles;
    stats_.bytes = accel_.memoryBytes();
  }

  Tracer kind() const override { return Tracer::Native; }
  AccelStats stats() const override { return stats_; }
  vk::Spirv shader(TraceShader which) const override {
    switch (which) {
      case TraceShader::Shadows: return vk::Spirv(kSpirv_rt_shadows_comp_native);
      case TraceShader::Effects: return vk::Spirv(kSpirv_rt_effects_comp_native);
      case TraceShader::ReflectionProbe: break;
    }
    return vk::Spirv(kSpirv_probe_capture_comp_native);
  }

  // The TLAS, and the geometry table in both other bindings (the layout keeps one shape).
  void writeBindings(VkDevice device, VkDescriptorSet set, std::span<const uint32_t> only) const override {
    const VkAccelerationStructureKHR tlas = accel_.tlas();
    VkWriteDescriptorSetAccelerationStructureKHR tlasWrite{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
    tlasWrite.accelerationStructureCount = 1;
    tlasWrite.pAccelerationStructures = &tlas;
    const VkDescriptorBufferInfo table{accel_.geometryTable().buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w[3];
    for (uint32_t i = 0; i < 3; ++i) {
      w[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w[i].dstSet = set;
      w[i].dstBinding = kBvhNodes + i;
      w[i].descriptorCount = 1;
      w[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      w[i].pBufferInfo = i == 0 ? nullptr : &table;
    }
    w[0].pNext = &tlasWrite;
    updateBindingsAmong(device, w, only);
  }

  double recordMovedObjects(VkCommandBuffer cmd, const Scene& shell, std::span<const gpu::GpuObject> records, vk::Buffer& staging,
                            const vk::Buffer& objectRecords) override {
    const auto start = std::chrono::steady_clock::now();
    const VkDeviceSize instBytes = accel_.instanceBytes(), objBytes = records.size_bytes();
    uint8_t* dst = stagingOf(ctx_, staging, instBytes + objBytes);
    accel_.writeInstances(shell.objects, dst);
    std::memcpy(dst + instBytes, records.data(), objBytes);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const VkBufferCopy objects{instBytes, 0, objBytes};
    vkCmdCopyBuffer(cmd, staging.buffer, objectRecords.buffer, 1, &objects);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_MEMORY_READ_BIT);
    accel_.recordTlasBuild(cmd, staging.buffer, 0);  // copies the instances, rebuilds, with its barriers
    return ms;
  }

 private:
  const vk::Context& ctx_;
  NativeAccel accel_;
  AccelStats stats_;
};

}  // namespace

std::unique_ptr<SceneTracer> createNativeTracer(const vk::Context& ctx, const Scene& scene) {
  return std::make_unique<NativeTracer>(ctx, scene);
}

}  // namespace raybudget::passes
