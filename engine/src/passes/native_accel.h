// Vulkan acceleration structures for the native VK_KHR_ray_query tracer (--tracer native):
// one BLAS per mesh with one geometry per glTF primitive (opaque unless alpha-masked), a
// TLAS over the objects, and the geometry table that turns a hit's (instance SBT offset +
// geometry index, primitive index) into the mesh triangle and material numbers the compute
// tracer reports, so effect shaders read hits the same way from either tracer.
#pragma once
#include <span>

#include "raybudget/scene.h"
#include "vk/context.h"
#include "vk/resources.h"

namespace raybudget::passes {

class NativeAccel {
 public:
  // Builds every BLAS and the TLAS on the device (waits for the build).
  NativeAccel(const vk::Context& ctx, const Scene& scene);

  VkAccelerationStructureKHR tlas() const { return tlas_; }
  // uvec2 per geometry: the mesh triangle its primitive starts at, and its material.
  const vk::Buffer& geometryTable() const { return geometryTable_; }
  double buildMs() const { return buildMs_; }  // BLAS + TLAS, wall clock including the upload
  size_t memoryBytes() const { return memoryBytes_; }

  // Rebuilding the TLAS for moved objects: the instance records go to `staging` (host
  // visible, instanceBytes() long at `offset`); recordTlasBuild then copies them and
  // rebuilds, with the barriers that order it after earlier and before later shader reads.
  size_t instanceBytes() const;
  void writeInstances(std::span<const Object> objects, void* staging);
  void recordTlasBuild(VkCommandBuffer cmd, VkBuffer staging, VkDeviceSize offset) const;

 private:
  struct Blas {
    vk::Buffer storage;
    vk::Owned<VkAccelerationStructureKHR> handle;
    VkDeviceAddress address = 0;
    uint32_t geometryBase = 0;  // index of its first geometry in the geometry table
  };

  const vk::Context& ctx_;
  std::vector<Blas> blas_;  // per mesh; handle is null for a mesh without triangles
  vk::Buffer geometryTable_;
  vk::Buffer instances_;
  uint32_t instanceCount_ = 0;
  vk::Buffer tlasStorage_;
  vk::Buffer tlasScratch_;
  vk::Owned<VkAccelerationStructureKHR> tlas_;
  double buildMs_ = 0.0;
  size_t memoryBytes_ = 0;
};

}  // namespace raybudget::passes
