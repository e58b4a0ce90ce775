#include "passes/native_accel.h"

#include <chrono>
#include <cstring>

#include "vk/check.h"

namespace raybudget::passes {
namespace {

constexpr VkBufferUsageFlags kAddress = VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
constexpr VkBufferUsageFlags kBuildInput = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | kAddress;

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

// An acceleration structure of `type` in a fresh buffer of `size` bytes.
vk::Owned<VkAccelerationStructureKHR> createAccel(const vk::Context& ctx, VkAccelerationStructureTypeKHR type, VkDeviceSize size,
                                                  vk::Buffer& storage) {
  storage = vk::createBuffer(ctx, size, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | kAddress, false);
  VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  ci.buffer = storage.buffer;
  ci.size = size;
  ci.type = type;
  VkAccelerationStructureKHR as = VK_NULL_HANDLE;
  VK_CHECK(ctx.accel().create(ctx.device(), &ci, nullptr, &as));
  const VkDevice device = ctx.device();
  const auto destroy = ctx.accel().destroy;
  return vk::Owned<VkAccelerationStructureKHR>(as, [device, destroy](VkAccelerationStructureKHR a) { destroy(device, a, nullptr); });
}

VkAccelerationStructureGeometryKHR instanceGeometry(VkDeviceAddress instances) {
  VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  g.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  g.geometry.instances = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR};
  g.geometry.instances.data.deviceAddress = instances;
  return g;
}

}  // namespace

NativeAccel::NativeAccel(const vk::Context& ctx, const Scene& scene) : ctx_(ctx) {
  if (!ctx.rayQuerySupported())
    throw Error(std::string(ctx.properties().deviceName) + " does not offer VK_KHR_ray_query with acceleration structures; use --tracer compute");
  const auto start = std::chrono::steady_clock::now();
  const VkDevice device = ctx.device();
  const vk::AccelFunctions& fn = ctx.accel();

  // Build inputs: every mesh's positions and indices in two buffers, and the geometry table.
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
  std::vector<glm::uvec2> table;
  std::vector<VkDeviceSize> vertexBase, indexBase;
  for (const Mesh& m : scene.meshes) {
    vertexBase.push_back(positions.size());
    indexBase.push_back(indices.size());
    for (const Vertex& v : m.vertices) positions.push_back(v.position);
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
  }
  vk::Buffer positionBuffer = vk::createDeviceBuffer(ctx, positions, kBuildInput);
  vk::Buffer indexBuffer = vk::createDeviceBuffer(ctx, indices, kBuildInput);
  const VkDeviceAddress positionAddress = vk::bufferAddress(ctx, positionBuffer), indexAddress = vk::bufferAddress(ctx, indexBuffer);

  // One BLAS per mesh, all built in one command with separate scratch ranges.
  std::vector<std::vector<VkAccelerationStructureGeometryKHR>> geometries(scene.meshes.size());
  std::vector<std::vector<VkAccelerationStructureBuildRangeInfoKHR>> ranges(scene.meshes.size());
  std::vector<VkAccelerationStructureBuildGeometryInfoKHR> builds;
  std::vector<VkDeviceSize> scratchOffsets;
  VkDeviceSize scratchSize = 0;
  blas_.resize(scene.meshes.size());
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& m = scene.meshes[mi];
    blas_[mi].geometryBase = uint32_t(table.size());
    std::vector<uint32_t> counts;
    for (const Primitive& p : m.primitives) {
      if (p.indexCount < 3) continue;
      const Material& mat = scene.materials[size_t(p.material)];
      VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
      g.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
      g.flags = mat.alphaMode == AlphaMode::Mask ? VkGeometryFlagsKHR(0) : VkGeometryFlagsKHR(VK_GEOMETRY_OPAQUE_BIT_KHR);
      auto& tri = g.geometry.triangles;
      tri = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR};
      tri.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
      tri.vertexData.deviceAddress = positionAddress + vertexBase[mi] * sizeof(glm::vec3);
      tri.vertexStride = sizeof(glm::vec3);
      tri.maxVertex = uint32_t(m.vertices.size()) - 1;
      tri.indexType = VK_INDEX_TYPE_UINT32;
      tri.indexData.deviceAddress = indexAddress + (indexBase[mi] + p.firstIndex) * sizeof(uint32_t);
      geometries[mi].push_back(g);
      ranges[mi].push_back({p.indexCount / 3, 0, 0, 0});
      counts.push_back(p.indexCount / 3);
      table.push_back({p.firstIndex / 3, uint32_t(p.material)});
    }
    if (geometries[mi].empty()) continue;
    VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    info.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
    info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
    info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    info.geometryCount = uint32_t(geometries[mi].size());
    info.pGeometries = geometries[mi].data();
    VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    fn.buildSizes(device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info, counts.data(), &sizes);
    blas_[mi].handle = createAccel(ctx, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, sizes.accelerationStructureSize, blas_[mi].storage);
    memoryBytes_ += sizes.accelerationStructureSize;
    info.dstAccelerationStructure = blas_[mi].handle;
    scratchOffsets.push_back(scratchSize);
    scratchSize = alignUp(scratchSize + sizes.buildScratchSize, ctx.accelScratchAlignment());
    builds.push_back(info);
  }
  if (table.empty()) table.push_back({0, 0});  // descriptors must point somewhere
  geometryTable_ = vk::createDeviceBuffer(ctx, table, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

  // The TLAS: sized for every object, rebuilt whole when objects move.
  instances_ = vk::createBuffer(ctx, std::max<size_t>(1, scene.objects.size()) * sizeof(VkAccelerationStructureInstanceKHR),
                                kBuildInput | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
  VkAccelerationStructureGeometryKHR tlasGeometry = instanceGeometry(vk::bufferAddress(ctx, instances_));
  VkAccelerationStructureBuildGeometryInfoKHR tlasInfo{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  tlasInfo.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  tlasInfo.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  tlasInfo.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  tlasInfo.geometryCount = 1;
  tlasInfo.pGeometries = &tlasGeometry;
  const uint32_t maxInstances = uint32_t(scene.objects.size());
  VkAccelerationStructureBuildSizesInfoKHR tlasSizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  fn.buildSizes(device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &tlasInfo, &maxInstances, &tlasSizes);
  tlas_ = createAccel(ctx, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, tlasSizes.accelerationStructureSize, tlasStorage_);
  memoryBytes_ += tlasSizes.accelerationStructureSize;
  tlasScratch_ = vk::createBuffer(ctx, tlasSizes.buildScratchSize + ctx.accelScratchAlignment(),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | kAddress, false);
  for (Blas& b : blas_) {
    if (!b.handle) continue;
    VkAccelerationStructureDeviceAddressInfoKHR ai{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
    ai.accelerationStructure = b.handle;
    b.address = fn.deviceAddress(device, &ai);
  }

  vk::Buffer scratch = vk::createBuffer(ctx, scratchSize + ctx.accelScratchAlignment(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | kAddress, false);
  const VkDeviceAddress scratchAddress = alignUp(vk::bufferAddress(ctx, scratch), ctx.accelScratchAlignment());
  std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> rangePtrs;
  for (size_t i = 0, b = 0; i < scene.meshes.size(); ++i) {
    if (geometries[i].empty()) continue;
    builds[b].scratchData.deviceAddress = scratchAddress + scratchOffsets[b];
    rangePtrs.push_back(ranges[i].data());
    ++b;
  }
  vk::Buffer staging = vk::createBuffer(ctx, instanceBytes(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
  writeInstances(scene.objects, staging.mapped);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    if (!builds.empty()) fn.cmdBuild(cmd, uint32_t(builds.size()), builds.data(), rangePtrs.data());
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                      VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
    recordTlasBuild(cmd, staging.buffer, 0);
  });
  buildMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

size_t NativeAccel::instanceBytes() const { return size_t(instances_.size); }

void NativeAccel::writeInstances(std::span<const Object> objects, void* staging) {
  std::vector<VkAccelerationStructureInstanceKHR> records;
  for (const Object& o : objects) {
    const Blas& b = blas_[o.mesh];
    if (!b.handle) continue;  // a mesh whose triangles were all dropped
    if (o.id >= (1u << 24)) throw Error("object " + std::to_string(o.id) + " exceeds the 24-bit instance index of VK_KHR_acceleration_structure");
    VkAccelerationStructureInstanceKHR r{};
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 4; ++col) r.transform.matrix[row][col] = o.transform[col][row];
    r.instanceCustomIndex = o.id;
    r.mask = 0xFF;
    r.instanceShaderBindingTableRecordOffset = b.geometryBase;
    // Facing as in the compute tracer (counter-clockwise seen from the ray origin is front):
    // Vulkan's default, since its ray space has y pointing the other way from DXR's; the
    // native-vs-compute test checks it.
    r.flags = 0;
    r.accelerationStructureReference = b.address;
    records.push_back(r);
  }
  std::memset(staging, 0, instanceBytes());
  std::memcpy(staging, records.data(), records.size() * sizeof(records[0]));
  instanceCount_ = uint32_t(records.size());
}

void NativeAccel::recordTlasBuild(VkCommandBuffer cmd, VkBuffer staging, VkDeviceSize offset) const {
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const VkBufferCopy copy{offset, 0, instanceBytes()};
  vkCmdCopyBuffer(cmd, staging, instances_.buffer, 1, &copy);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                    VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_2_SHADER_READ_BIT);
  VkAccelerationStructureGeometryKHR geometry = instanceGeometry(vk::bufferAddress(ctx_, instances_));
  VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  info.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  info.dstAccelerationStructure = tlas_;
  info.geometryCount = 1;
  info.pGeometries = &geometry;
  info.scratchData.deviceAddress = alignUp(vk::bufferAddress(ctx_, tlasScratch_), ctx_.accelScratchAlignment());
  const VkAccelerationStructureBuildRangeInfoKHR range{instanceCount_, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  ctx_.accel().cmdBuild(cmd, 1, &info, &ranges);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
}

}  // namespace raybudget::passes
