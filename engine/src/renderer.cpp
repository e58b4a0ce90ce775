// The standalone renderer: a host of the core (raybudget/core.h) through its public API.
// It owns a Vulkan device (or borrows a host's), a command buffer and a fence per frame
// slot, submits what the core records, and reads the images back.
#include "raybudget/renderer.h"

#include <algorithm>
#include <cstring>

#include "passes/descriptors.h"
#include "raybudget/testing.h"
#include "vk/check.h"
#include "vk/context.h"
#include "vk/memory_budget.h"
#include "vk/resources.h"

namespace raybudget {
namespace {

constexpr uint32_t kSlots = 2;  // the core's frame slots

// The borrowed view of the renderer's own device, for the core.
core::HostDevice hostDeviceOf(const vk::Context& ctx) {
  return {ctx.instance(), ctx.physicalDevice(), ctx.device(), ctx.queueFamily(), ctx.queue(), vkGetDeviceProcAddr, ctx.rayQuerySupported(),
          ctx.shaderFloat64()};
}

// An image of the core's, copied to a host-visible buffer and back to the layout it stays in.
struct ReadSource {
  VkImage image;
  VkImageAspectFlags aspect;
  VkImageLayout layout;
  VkDeviceSize bytes;
  uint32_t layers;
};

}  // namespace

struct Renderer::Impl {
  struct Slot {
    vk::Owned<VkCommandBuffer> cmd;
    vk::Owned<VkFence> fence;
    bool inFlight = false;
  };

  RenderSettings settings;
  std::unique_ptr<vk::Context> device;  // the renderer's own device, or a borrowed view of the host's
  core::Context core;
  vk::Owned<VkCommandPool> commandPool;
  Slot slots[kSlots];

  Impl(const Scene& scene, const RenderSettings& rs, std::unique_ptr<vk::Context> d, const testing::Checks& checks)
      : settings(rs), device(std::move(d)), core(hostDeviceOf(*device), scene, rs, checks) {
    VkCommandPoolCreateInfo ci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    ci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    ci.queueFamilyIndex = device->queueFamily();
    const VkDevice dev = device->device();
    VkCommandPool pool = VK_NULL_HANDLE;
    VK_CHECK(vkCreateCommandPool(dev, &ci, nullptr, &pool));
    commandPool = vk::Owned<VkCommandPool>(pool, [dev](VkCommandPool p) { vkDestroyCommandPool(dev, p, nullptr); });
    for (Slot& slot : slots) {
      VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
      ai.commandPool = commandPool;
      ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
      ai.commandBufferCount = 1;
      VkCommandBuffer cmd = VK_NULL_HANDLE;
      VK_CHECK(vkAllocateCommandBuffers(dev, &ai, &cmd));
      slot.cmd = vk::Owned<VkCommandBuffer>(cmd, [dev, pool](VkCommandBuffer c) { vkFreeCommandBuffers(dev, pool, 1, &c); });
      VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
      VkFence fence = VK_NULL_HANDLE;
      VK_CHECK(vkCreateFence(dev, &fci, nullptr, &fence));
      slot.fence = vk::Owned<VkFence>(fence, [dev](VkFence f) { vkDestroyFence(dev, f, nullptr); });
    }
  }

  // Waits for the slot's previous frame (submitted kSlots frames ago).
  void wait(Slot& slot) {
    if (!slot.inFlight) return;
    VkFence fence = slot.fence;
    VK_CHECK(vkWaitForFences(device->device(), 1, &fence, VK_TRUE, UINT64_MAX));
    VK_CHECK(vkResetFences(device->device(), 1, &fence));
    slot.inFlight = false;
  }

  std::vector<FrameTiming> render(const Camera& camera) {
    validateCamera(camera, "render");  // before anything is recorded
    Slot& slot = slots[core.framesRecorded() % kSlots];
    wait(slot);
    VkCommandBuffer cmd = slot.cmd;
    VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
    core.recordFrame(cmd, camera);  // the core's own G-buffer raster
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    VK_CHECK(vkQueueSubmit(device->queue(), 1, &si, slot.fence));
    slot.inFlight = true;
    return core.completedFrames();
  }

  std::vector<FrameTiming> finish() {
    for (Slot& slot : slots) wait(slot);
    return core.completedFrames(true);
  }

  // Teardown: waits for the frames in flight without reading them.
  void waitForFrames() {
    for (Slot& slot : slots)
      if (slot.inFlight) {
        VkFence fence = slot.fence;
        vkWaitForFences(device->device(), 1, &fence, VK_TRUE, UINT64_MAX);  // no throw in a destructor
      }
  }

  FrameImages readback(bool gbufferDetail) {
    if (core.framesRecorded() == 0) throw Error("readback() before any frame was rendered");
    VK_CHECK(vkQueueWaitIdle(device->queue()));
    const core::FrameOutputs out = core.outputs();
    const core::OwnGBuffer g = core.ownGBuffer();
    const VkDeviceSize pixels = VkDeviceSize(settings.width) * settings.height;
    const VkImageAspectFlags color = VK_IMAGE_ASPECT_COLOR_BIT;
    const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL, readOnly = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    std::vector<ReadSource> sources = {{out.ldr, color, general, pixels * 4, 1},
                                       {out.hdr, color, general, pixels * 8, 1},
                                       {g.objectId, color, readOnly, pixels * 4, 1}};
    if (gbufferDetail) {
      const uint32_t lights = out.shadowVisibilityLayers;
      sources.push_back({g.position, color, readOnly, pixels * 16, 1});
      sources.push_back({out.shadowVisibility, color, general, pixels * 4 * lights, lights});
      sources.push_back({g.normal, color, readOnly, pixels * 8, 1});
      sources.push_back({g.roughTransIor, color, readOnly, pixels * 8, 1});
      sources.push_back({g.baseMetal, color, readOnly, pixels * 4, 1});
      sources.push_back({g.depth, VK_IMAGE_ASPECT_DEPTH_BIT, readOnly, pixels * 4, 1});
      sources.push_back({g.emissive, color, readOnly, pixels * 8, 1});
      sources.push_back({g.materialId, color, readOnly, pixels * 4, 1});
      sources.push_back({out.tracedMask, color, general, pixels * 4, 1});
    }
    std::vector<vk::Buffer> buffers;
    for (const ReadSource& src : sources) buffers.push_back(vk::createBuffer(*device, src.bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true));
    device->submitAndWait([&](VkCommandBuffer cmd) {
      // Each source goes to TRANSFER_SRC for its copy and back to the layout the frame expects.
      for (size_t i = 0; i < sources.size(); ++i) {
        const ReadSource& src = sources[i];
        vk::imageBarrier(cmd, src.image, src.aspect, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, src.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {src.aspect, 0, 0, src.layers};
        copy.imageExtent = {settings.width, settings.height, 1};
        vkCmdCopyImageToBuffer(cmd, src.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffers[i].buffer, 1, &copy);
        vk::imageBarrier(cmd, src.image, src.aspect, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, src.layout);
      }
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                        VK_ACCESS_2_HOST_READ_BIT);
    });
    FrameImages images;
    images.width = settings.width;
    images.height = settings.height;
    auto take = [&](auto& vec, size_t i) {
      vec.resize(size_t(sources[i].bytes) / sizeof(vec[0]));
      std::memcpy(vec.data(), buffers[i].mapped, size_t(sources[i].bytes));
    };
    take(images.ldrRgba8, 0);
    take(images.hdrRgba16, 1);
    take(images.objectIds, 2);
    if (gbufferDetail) {
      take(images.positions, 3);
      take(images.shadowMask, 4);
      take(images.normals, 5);
      take(images.roughTransIor, 6);
      take(images.baseMetal, 7);
      take(images.depth, 8);
      take(images.emissive, 9);
      take(images.materialIds, 10);
      take(images.tracedMask, 11);
    }
    return images;
  }
};

Renderer::Renderer(const Scene& scene, const RenderSettings& settings) : Renderer(scene, settings, testing::Checks{}) {}

Renderer::Renderer(const Scene& scene, const RenderSettings& settings, const testing::Checks& checks) {
  validateSettings(settings);
  const vk::DescriptorNeeds needs = passes::descriptorNeeds(uint32_t(scene.textures.size()), false);
  impl_ = std::make_unique<Impl>(scene, settings, std::make_unique<vk::Context>(vk::ContextOptions{settings.validation, settings.device, needs}),
                                 checks);
}

Renderer::Renderer(const Scene& scene, const RenderSettings& settings, const core::HostDevice& host) {
  validateSettings(settings);
  if (settings.validation || !settings.device.empty())
    throw Error("RenderSettings::validation and ::device choose the renderer's own device; on a host's device the host's instance decides them");
  impl_ = std::make_unique<Impl>(scene, settings, std::make_unique<vk::Context>(host), testing::Checks{});
}

Renderer::~Renderer() {
  if (impl_) impl_->waitForFrames();
}

std::vector<FrameTiming> Renderer::render(const Camera& camera) { return impl_->render(camera); }

std::vector<FrameTiming> Renderer::finish() { return impl_->finish(); }

std::vector<FrameTiming> Renderer::restartSelection(Policy policy, float budgetMs, BenefitAblation ablation, ItemRate rate) {
  RenderSettings next = impl_->settings;
  next.policy = policy;
  next.budgetMs = budgetMs;
  next.benefitAblation = ablation;
  next.rayTracing.rate = rate;
  validateSettings(next);  // before waiting: a bad budget changes nothing
  std::vector<FrameTiming> done = finish();
  impl_->core.restartSelection(policy, budgetMs, ablation, rate);  // the core keeps the policy
  return done;
}

CostModel Renderer::costModel() const { return impl_->core.costModel(); }

void Renderer::setCostModel(const CostModel& model) { impl_->core.setCostModel(model); }

void Renderer::setObjectTransform(uint32_t objectId, const glm::mat4& transform) { impl_->core.setObjectTransform(objectId, transform); }

void Renderer::setObjectParams(uint32_t objectId, const RayBudgetParams& params) { impl_->core.setObjectParams(objectId, params); }

RayBudgetParams Renderer::objectParams(uint32_t objectId) const { return impl_->core.objectParams(objectId); }

std::vector<ObjectMetrics> Renderer::objectMetrics() { return impl_->core.objectMetrics(); }

FrameImages Renderer::readback(bool gbufferDetail) { return impl_->readback(gbufferDetail); }

AccelStats Renderer::accelStats() const { return impl_->core.accelStats(); }

SceneEffects Renderer::sceneEffects() const { return impl_->core.sceneEffects(); }

std::vector<std::string> Renderer::builtPipelines() const { return impl_->core.builtPipelines(); }

std::string Renderer::deviceName() const { return impl_->device->properties().deviceName; }

DeviceMemoryUsage Renderer::deviceMemoryUsage() const { return vk::memoryUsage(impl_->device->physicalDevice()); }

uint64_t Renderer::allocatedBytes() const { return impl_->device->allocatedBytes() + impl_->core.allocatedBytes(); }

void Renderer::setBudget(float budgetMs) {
  impl_->core.setBudget(budgetMs);
  impl_->settings.budgetMs = budgetMs;
}

std::vector<std::string> Renderer::validationMessages() const { return impl_->device->validationMessages(); }

float Renderer::aspect() const { return float(impl_->settings.width) / float(impl_->settings.height); }

}  // namespace raybudget
