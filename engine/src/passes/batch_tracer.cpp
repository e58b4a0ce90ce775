#include "passes/batch_tracer.h"

#include <cstring>

#include "trace_rays_comp.h"
#include "vk/check.h"
#include "vk/pipelines.h"
#include "vk/resources.h"
#include "vk/timestamps.h"

namespace raybudget::passes {
namespace {

constexpr uint32_t kBindings = 5;  // nodes, triangles, instances, rays, hits
constexpr uint32_t kGroupSize = 64;
constexpr uint32_t kTexelBindings = 2;  // nodes and triangles are read as texels (rayquery.glsl)
constexpr VkBufferUsageFlags kTexels = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;

VkDescriptorType bindingType(uint32_t binding) {
  return binding < kTexelBindings ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

struct Push {
  uint32_t count;
  uint32_t flags;
};

}  // namespace

struct BatchTracer::Impl {
  const vk::Context& ctx;
  vk::Buffer nodes, triangles, instances;
  vk::Owned<VkBufferView> nodeTexels, triangleTexels;
  vk::Owned<VkDescriptorSetLayout> setLayout;
  vk::Owned<VkPipelineLayout> layout;
  vk::Owned<VkPipeline> pipeline;
  vk::Owned<VkDescriptorPool> pool;
  vk::TimestampPool timestamps;
  double gpuMs = 0.0;

  Impl(const vk::Context& c, const bvh::SceneBvh& bvh)
      : ctx(c),
        nodes(vk::createDeviceBuffer(c, bvh.nodes, kTexels)),
        triangles(vk::createDeviceBuffer(c, bvh.triangles, kTexels)),
        instances(vk::createDeviceBuffer(c, bvh.instances, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT)),
        nodeTexels(vk::createTexelView(c, nodes, VK_FORMAT_R32G32B32A32_SFLOAT, 16)),
        triangleTexels(vk::createTexelView(c, triangles, VK_FORMAT_R32G32B32A32_SFLOAT, 16)),
        timestamps(c, 1, 1) {
    const VkDevice device = c.device();
    std::vector<VkDescriptorSetLayoutBinding> b;
    for (uint32_t i = 0; i < kBindings; ++i) b.push_back({i, bindingType(i), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = kBindings;
    lci.pBindings = b.data();
    VkDescriptorSetLayout sl = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorSetLayout(device, &lci, nullptr, &sl));
    setLayout = vk::Owned<VkDescriptorSetLayout>(sl, [device](VkDescriptorSetLayout x) { vkDestroyDescriptorSetLayout(device, x, nullptr); });
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(Push)};
    VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pci.setLayoutCount = 1;
    pci.pSetLayouts = &sl;
    pci.pushConstantRangeCount = 1;
    pci.pPushConstantRanges = &range;
    VkPipelineLayout pl = VK_NULL_HANDLE;
    VK_CHECK(vkCreatePipelineLayout(device, &pci, nullptr, &pl));
    layout = vk::Owned<VkPipelineLayout>(pl, [device](VkPipelineLayout x) { vkDestroyPipelineLayout(device, x, nullptr); });
    pipeline = vk::createComputePipeline(c, layout, kSpirv_trace_rays_comp);
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, kTexelBindings},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBindings - kTexelBindings}};
    VkDescriptorPoolCreateInfo dci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    dci.maxSets = 1;
    dci.poolSizeCount = 2;
    dci.pPoolSizes = sizes;
    VkDescriptorPool p = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorPool(device, &dci, nullptr, &p));
    pool = vk::Owned<VkDescriptorPool>(p, [device](VkDescriptorPool x) { vkDestroyDescriptorPool(device, x, nullptr); });
  }

  std::vector<gpu::GpuHit> trace(const std::vector<gpu::GpuRay>& rays, uint32_t flags) {
    if (rays.empty()) return {};
    const VkDeviceSize rayBytes = rays.size() * sizeof(gpu::GpuRay), hitBytes = rays.size() * sizeof(gpu::GpuHit);
    vk::Buffer rayBuffer = vk::createDeviceBuffer(ctx, rays.data(), rayBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vk::Buffer hitBuffer = vk::createBuffer(ctx, hitBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
    vk::Buffer readback = vk::createBuffer(ctx, hitBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);

    // The set is rewritten per batch (its buffers are new); the pool holds exactly one.
    VK_CHECK(vkResetDescriptorPool(ctx.device(), pool, 0));
    VkDescriptorSetLayout sl = setLayout;
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &sl;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateDescriptorSets(ctx.device(), &ai, &set));
    const VkBufferView texelViews[kTexelBindings] = {nodeTexels, triangleTexels};
    const VkDescriptorBufferInfo infos[kBindings] = {{},
                                                     {},
                                                     {instances.buffer, 0, VK_WHOLE_SIZE},
                                                     {rayBuffer.buffer, 0, VK_WHOLE_SIZE},
                                                     {hitBuffer.buffer, 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet writes[kBindings];
    for (uint32_t i = 0; i < kBindings; ++i) {
      writes[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      writes[i].dstSet = set;
      writes[i].dstBinding = i;
      writes[i].descriptorCount = 1;
      writes[i].descriptorType = bindingType(i);
      if (i < kTexelBindings) writes[i].pTexelBufferView = &texelViews[i];
      else writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(ctx.device(), kBindings, writes, 0, nullptr);

    const Push push{uint32_t(rays.size()), flags};
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      timestamps.reset(cmd, 0);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
      vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
      timestamps.begin(cmd, 0, 0);
      vkCmdDispatch(cmd, (push.count + kGroupSize - 1) / kGroupSize, 1, 1);
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
BatchTracer::~BatchTracer() = default;
std::vector<gpu::GpuHit> BatchTracer::trace(const std::vector<gpu::GpuRay>& rays, uint32_t flags) { return impl_->trace(rays, flags); }
double BatchTracer::lastGpuMs() const { return impl_->gpuMs; }

}  // namespace raybudget::passes
