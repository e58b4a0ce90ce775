#include "vk/device_requirements.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "vk/check.h"

namespace raybudget::vk {
namespace {

// The largest workgroup (select_bitonic.comp: 512 lanes) and its shared memory (1024 uvec2).
constexpr uint32_t kWorkgroupInvocations = 512;
constexpr uint32_t kSharedMemoryBytes = 1024 * 8;

const char* const kRayQueryExtensions[] = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME, VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                           VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};

std::optional<uint32_t> timestampQueueFamily(VkPhysicalDevice device) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &n, families.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (uint32_t i = 0; i < n; ++i)
    if ((families[i].queueFlags & need) == need && families[i].timestampValidBits > 0) return i;
  return std::nullopt;
}

std::string versionText(uint32_t v) { return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)); }

}  // namespace

std::vector<std::string> extensionNames(VkPhysicalDevice device) {
  uint32_t n = 0;
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &n, nullptr));
  std::vector<VkExtensionProperties> exts(n);
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &n, exts.data()));
  std::vector<std::string> names;
  for (const VkExtensionProperties& e : exts) names.push_back(e.extensionName);
  return names;
}

bool DeviceCapabilities::hasExtension(const char* ext) const { return std::find(extensions.begin(), extensions.end(), ext) != extensions.end(); }

DeviceCapabilities queryCapabilities(VkPhysicalDevice device) {
  DeviceCapabilities c;
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(device, &props);
  c.name = props.deviceName;
  c.apiVersion = props.apiVersion;
  c.limits = props.limits;
  c.extensions = extensionNames(device);
  c.queueFamily = timestampQueueFamily(device);
  // Vulkan 1.2/1.3 feature structures are only valid to query on a 1.2/1.3 device.
  if (c.apiVersion < VK_API_VERSION_1_3) {
    vkGetPhysicalDeviceFeatures(device, &c.features);
    return c;
  }
  VkPhysicalDeviceRayQueryFeaturesKHR rq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceShaderClockFeaturesKHR clock{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_CLOCK_FEATURES_KHR};
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f2.pNext = &f12;
  f12.pNext = &f13;
  // Extension feature structures may only be chained when the extension is offered.
  void** tail = &f13.pNext;
  if (c.hasExtension(VK_KHR_SHADER_CLOCK_EXTENSION_NAME)) *std::exchange(tail, &clock.pNext) = &clock;
  if (c.hasExtension(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME)) *std::exchange(tail, &as.pNext) = &as;
  if (c.hasExtension(VK_KHR_RAY_QUERY_EXTENSION_NAME)) *std::exchange(tail, &rq.pNext) = &rq;
  vkGetPhysicalDeviceFeatures2(device, &f2);
  c.features = f2.features;
  c.dynamicRendering = f13.dynamicRendering;
  c.synchronization2 = f13.synchronization2;
  c.maintenance4 = f13.maintenance4;
  c.runtimeDescriptorArray = f12.runtimeDescriptorArray;
  c.sampledImageArrayNonUniformIndexing = f12.shaderSampledImageArrayNonUniformIndexing;
  c.bufferDeviceAddress = f12.bufferDeviceAddress;
  c.hostQueryReset = f12.hostQueryReset;
  c.shaderSubgroupClock = clock.shaderSubgroupClock;
  c.shaderDeviceClock = clock.shaderDeviceClock;
  c.accelerationStructure = as.accelerationStructure;
  c.rayQuery = rq.rayQuery;
  return c;
}

std::vector<std::string> missingRequirements(const DeviceCapabilities& c, const DescriptorNeeds& needs) {
  std::vector<std::string> out;
  const std::string device = c.name + ": ";
  if (c.apiVersion < VK_API_VERSION_1_3) {
    out.push_back(device + "Vulkan 1.3 is required, the device offers " + versionText(c.apiVersion));
    return out;  // the feature structures below were not read
  }
  if (!c.hasExtension(VK_KHR_SHADER_CLOCK_EXTENSION_NAME))
    out.push_back(device + "lacks the extension " VK_KHR_SHADER_CLOCK_EXTENSION_NAME " (the trace passes time each item's work with it)");
  auto feature = [&](bool have, const char* name, const char* why) {
    if (!have) out.push_back(device + "lacks the feature " + name + " (" + why + ")");
  };
  feature(c.dynamicRendering, "dynamicRendering", "G-buffer and shadow-map raster");
  feature(c.synchronization2, "synchronization2", "every barrier");
  feature(c.maintenance4, "maintenance4", "glslang's SPIR-V 1.6 uses LocalSizeId");
  feature(c.runtimeDescriptorArray, "runtimeDescriptorArray", "the scene's texture array");
  feature(c.sampledImageArrayNonUniformIndexing, "shaderSampledImageArrayNonUniformIndexing", "per-pixel material textures");
  feature(c.features.imageCubeArray, "imageCubeArray", "reflection probes");
  feature(!c.hasExtension(VK_KHR_SHADER_CLOCK_EXTENSION_NAME) || c.shaderSubgroupClock, "shaderSubgroupClock", "item cost measurement");
  feature(!c.hasExtension(VK_KHR_SHADER_CLOCK_EXTENSION_NAME) || c.shaderDeviceClock, "shaderDeviceClock", "the ray-tracing stage's deadline");
  auto limit = [&](uint32_t have, uint32_t need, const char* name) {
    if (have < need) out.push_back(device + name + " is " + std::to_string(have) + ", at least " + std::to_string(need) + " is needed");
  };
  const VkPhysicalDeviceLimits& l = c.limits;
  limit(l.maxPerStageDescriptorStorageBuffers, needs.storageBuffers, "maxPerStageDescriptorStorageBuffers");
  limit(l.maxPerStageDescriptorUniformBuffers, needs.uniformBuffers, "maxPerStageDescriptorUniformBuffers");
  limit(l.maxPerStageDescriptorSampledImages, needs.sampledImages, "maxPerStageDescriptorSampledImages");
  limit(l.maxPerStageDescriptorStorageImages, needs.storageImages, "maxPerStageDescriptorStorageImages");
  limit(l.maxPerStageDescriptorSamplers, needs.samplers, "maxPerStageDescriptorSamplers");
  limit(l.maxComputeWorkGroupInvocations, kWorkgroupInvocations, "maxComputeWorkGroupInvocations");
  limit(l.maxComputeWorkGroupSize[0], kWorkgroupInvocations, "maxComputeWorkGroupSize[0]");
  limit(l.maxComputeSharedMemorySize, kSharedMemoryBytes, "maxComputeSharedMemorySize");
  if (!c.queueFamily) out.push_back(device + "has no queue family with graphics, compute and timestamps (every pass is timed)");
  return out;
}

bool offersRayQuery(const DeviceCapabilities& c) {
  const bool extensions = std::all_of(std::begin(kRayQueryExtensions), std::end(kRayQueryExtensions), [&](const char* e) { return c.hasExtension(e); });
  return extensions && c.rayQuery && c.accelerationStructure && c.bufferDeviceAddress;
}

core::DeviceSetup deviceSetup(const DeviceCapabilities& c) {
  core::DeviceSetup s;
  s.queueFamily = c.queueFamily.value_or(0);
  s.extensions.push_back(VK_KHR_SHADER_CLOCK_EXTENSION_NAME);
  s.shaderClock.shaderSubgroupClock = VK_TRUE;
  s.shaderClock.shaderDeviceClock = VK_TRUE;
  // Optional: lets Renderer::deviceMemoryUsage report the driver's figures.
  if (c.hasExtension(VK_EXT_MEMORY_BUDGET_EXTENSION_NAME)) s.extensions.push_back(VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
  s.vulkan13.dynamicRendering = VK_TRUE;
  s.vulkan13.synchronization2 = VK_TRUE;
  s.vulkan13.maintenance4 = VK_TRUE;
  s.vulkan12.runtimeDescriptorArray = VK_TRUE;
  s.vulkan12.shaderSampledImageArrayNonUniformIndexing = VK_TRUE;
  s.vulkan12.hostQueryReset = c.hostQueryReset;
  s.features.features.imageCubeArray = VK_TRUE;
  s.features.features.samplerAnisotropy = c.features.samplerAnisotropy;
  s.features.features.shaderStorageImageWriteWithoutFormat = c.features.shaderStorageImageWriteWithoutFormat;
  // 64-bit floats give the GPU selection correctly rounded quotients (select_common.glsl).
  s.shaderFloat64Enabled = c.features.shaderFloat64 == VK_TRUE;
  s.features.features.shaderFloat64 = c.features.shaderFloat64;
  s.rayQueryEnabled = offersRayQuery(c);
  if (s.rayQueryEnabled) {
    s.extensions.insert(s.extensions.end(), std::begin(kRayQueryExtensions), std::end(kRayQueryExtensions));
    s.rayQuery.rayQuery = VK_TRUE;
    s.accelerationStructure.accelerationStructure = VK_TRUE;
    s.vulkan12.bufferDeviceAddress = VK_TRUE;
  }
  return s;
}

}  // namespace raybudget::vk

namespace raybudget::core {

void* DeviceSetup::chain(void* next) {
  features.pNext = &vulkan12;
  vulkan12.pNext = &vulkan13;
  vulkan13.pNext = &shaderClock;
  if (rayQueryEnabled) {
    shaderClock.pNext = &accelerationStructure;
    accelerationStructure.pNext = &rayQuery;
    rayQuery.pNext = next;
  } else {
    shaderClock.pNext = next;
  }
  return &features;
}

}  // namespace raybudget::core
