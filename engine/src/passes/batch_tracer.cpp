#include "passes/batch_tracer.h"

#include <chrono>
#include <cstring>

#include "bvh/ray_binning.h"
#include "passes/bvh_buffers.h"
#include "passes/native_accel.h"
#include "shared/config.h"
#include "trace_rays_comp.h"
#include "trace_rays_comp_native.h"
#include "vk/check.h"
#include "vk/compute_set.h"
#include "vk/pipelines.h"
#include "vk/resources.h"
#include "vk/timestamps.h"

namespace raybudget::passes {
namespace {

// Bindings of trace_rays.comp: the tracer's three (rayquery.glsl), then rays and hits.
constexpr uint32_t kRays = 3, kHits = 4;

struct Push {
  uint32_t count;
  uint32_t flags;
};

// One descriptor of the set: what it is and what it points at.
struct Binding {
  uint32_t binding;
  VkDescriptorType type;
  VkDescriptorBufferInfo buffer{};
  VkBufferView texels = VK_NULL_HANDLE;
  VkAccelerationStructureKHR accel = VK_NULL_HANDLE;
};

}  // namespace

struct BatchTracer::Impl {
  const vk::Context& ctx;
  // Compute tracer: our BVH. Native: acceleration structures.
  BvhBuffers bvhBuffers;
  std::unique_ptr<NativeAccel> native;
  std::vector<Binding> bindings;  // the tracer's; rays and hits are added per batch
  vk::Owned<VkDescriptorSetLayout> setLayout;
  vk::Owned<VkPipelineLayout> layout;
  vk::Owned<VkPipeline> pipeline;
  vk::Owned<VkDescriptorPool> pool;
  vk::TimestampPool timestamps;
  double gpuMs = 0.0, binMs = 0.0;
  bvh::RayBinner binner;  // Order::Binned keeps its buffers between batches
  std::vector<gpu::GpuRay> binnedRays;
  size_t accelBytes = 0;

  Impl(const vk::Context& c, const bvh::SceneBvh& bvh) : ctx(c), timestamps(c, 1, 1) {
    bvhBuffers = uploadBvh(c, bvh, false);
    accelBytes = bvhBuffers.bytes();
    Binding n{0, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER}, t{1, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER};
    n.texels = bvhBuffers.nodeTexels;
    t.texels = bvhBuffers.triangleTexels;
    bindings = {n, t, {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, {bvhBuffers.instances.buffer, 0, VK_WHOLE_SIZE}}};
    createPipeline(kSpirv_trace_rays_comp);
  }

  Impl(const vk::Context& c, const Scene& scene) : ctx(c), native(std::make_unique<NativeAccel>(c, scene)), timestamps(c, 1, 1) {
    accelBytes = native->memoryBytes();
    Binding tlas{0, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR};
    tlas.accel = native->tlas();
    bindings = {tlas, {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, {native->geometryTable().buffer, 0, VK_WHOLE_SIZE}}};
    createPipeline(kSpirv_trace_rays_comp_native);
  }

  void createPipeline(vk::Spirv shader) {
    std::vector<VkDescriptorSetLayoutBinding> b;
    std::vector<VkDescriptorPoolSize> sizes;
    for (const Binding& x : bindings) {
      b.push_back({x.binding, x.type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
      sizes.push_back({x.type, 1});
    }
    for (uint32_t i : {kRays, kHits}) b.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2});
    setLayout = vk::createSetLayout(ctx, b);
    layout = vk::createPipelineLayout(ctx, setLayout, VK_SHADER_STAGE_COMPUTE_BIT, sizeof(Push));
    pipeline = vk::createComputePipeline(ctx, layout, shader);
    pool = vk::createPool(ctx, sizes, 1, VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT);
  }

  // The set is rewritten per batch (its ray and hit buffers are new); the pool holds one.
  VkDescriptorSet writeSet(const vk::Buffer& rays, const vk::Buffer& hits) {
    VK_CHECK(vkResetDescriptorPool(ctx.device(), pool, 0));
    VkDescriptorSetLayout sl = setLayout;
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &sl;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateDescriptorSets(ctx.device(), &ai, &set));
    std::vector<Binding> all = bindings;
    all.push_back({kRays, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, {rays.buffer, 0, VK_WHOLE_SIZE}});
    all.push_back({kHits, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, {hits.buffer, 0, VK_WHOLE_SIZE}});
    std::vector<VkWriteDescriptorSet> writes(all.size());
    std::vector<VkWriteDescriptorSetAccelerationStructureKHR> accels(all.size());
    for (size_t i = 0; i < all.size(); ++i) {
      VkWriteDescriptorSet& w = writes[i];
      w = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w.dstSet = set;
      w.dstBinding = all[i].binding;
      w.descriptorCount = 1;
      w.descriptorType = all[i].type;
      if (all[i].type == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) {
        w.pTexelBufferView = &all[i].texels;
      } else if (all[i].type == VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR) {
        accels[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
        accels[i].accelerationStructureCount = 1;
        accels[i].pAccelerationStructures = &all[i].accel;
        w.pNext = &accels[i];
      } else {
        w.pBufferInfo = &all[i].buffer;
      }
    }
    vkUpdateDescriptorSets(ctx.device(), uint32_t(writes.size()), writes.data(), 0, nullptr);
    return set;
  }

  std::vector<gpu::GpuHit> trace(const std::vector<gpu::GpuRay>& rays, uint32_t flags, Order order) {
    binMs = 0.0;
    if (order == Order::AsGiven) return dispatch(rays, flags);
    const auto start = std::chrono::steady_clock::now();
    const std::vector<uint32_t>& binned = binner.bin(rays);
    binnedRays.resize(rays.size());
    for (size_t i = 0; i < binned.size(); ++i) binnedRays[i] = rays[binned[i]];
    binMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const std::vector<gpu::GpuHit> sortedHits = dispatch(binnedRays, flags);
    std::vector<gpu::GpuHit> hits(rays.size());
    for (size_t i = 0; i < binned.size(); ++i) hits[binned[i]] = sortedHits[i];
    return hits;
  }

  std::vector<gpu::GpuHit> dispatch(const std::vector<gpu::GpuRay>& rays, uint32_t flags) {
    if (rays.empty()) return {};
    const VkDeviceSize rayBytes = rays.size() * sizeof(gpu::GpuRay), hitBytes = rays.size() * sizeof(gpu::GpuHit);
    vk::Buffer rayBuffer = vk::createDeviceBuffer(ctx, rays.data(), rayBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vk::Buffer hitBuffer = vk::createBuffer(ctx, hitBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
    vk::Buffer readback = vk::createBuffer(ctx, hitBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    const VkDescriptorSet set = writeSet(rayBuffer, hitBuffer);
    const Push push{uint32_t(rays.size()), flags};
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      timestamps.reset(cmd, 0);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
      vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
      timestamps.begin(cmd, 0, 0);
      vkCmdDispatch(cmd, vk::groupsFor(push.count, RB_GROUP_SIZE), 1, 1);
      timestamps.end(cmd, 0, 0);
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                        VK_ACCESS_2_TRANSFER_READ_BIT);
      const VkBufferCopy copy{0, 0, hitBytes};
      vkCmdCopyBuffer(cmd, hitBuffer.buffer, readback.buffer, 1, &copy);
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    gpuMs = timestamps.read(0)[0].value_or(0.0);
    std::vector<gpu::GpuHit> hits(rays.size());
    std::memcpy(hits.data(), readback.mapped, size_t(hitBytes));
    return hits;
  }
};

BatchTracer::BatchTracer(const vk::Context& ctx, const bvh::SceneBvh& bvh) : impl_(std::make_unique<Impl>(ctx, bvh)) {}
BatchTracer::BatchTracer(const vk::Context& ctx, const Scene& scene) : impl_(std::make_unique<Impl>(ctx, scene)) {}
BatchTracer::~BatchTracer() = default;
std::vector<gpu::GpuHit> BatchTracer::trace(const std::vector<gpu::GpuRay>& rays, uint32_t flags, Order order) {
  return impl_->trace(rays, flags, order);
}
double BatchTracer::lastGpuMs() const { return impl_->gpuMs; }
double BatchTracer::lastBinMs() const { return impl_->binMs; }
double BatchTracer::buildMs() const { return impl_->native ? impl_->native->buildMs() : 0.0; }
size_t BatchTracer::accelBytes() const { return impl_->accelBytes; }

}  // namespace raybudget::passes
