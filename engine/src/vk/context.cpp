#include "vk/context.h"

#include <algorithm>
#include <cstring>

#include "vk/check.h"

namespace raybudget::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
  static_cast<Context*>(user)->recordValidationMessage(std::string("validation ") + level + ": " + (data->pMessage ? data->pMessage : ""));
  return VK_FALSE;
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t n = 0;
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &n, nullptr));
  std::vector<VkExtensionProperties> exts(n);
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &n, exts.data()));
  return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool hasLayer(const char* name) {
  uint32_t n = 0;
  VK_CHECK(vkEnumerateInstanceLayerProperties(&n, nullptr));
  std::vector<VkLayerProperties> layers(n);
  VK_CHECK(vkEnumerateInstanceLayerProperties(&n, layers.data()));
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t n = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, nullptr));
  std::vector<VkPhysicalDevice> devices(n);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, devices.data()));
  return devices;
}

int typeRank(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

const char* typeName(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU (software)";
    default: return "other";
  }
}

Owned<VkInstance> createInstance(bool validation, Context* self, Owned<VkDebugUtilsMessengerEXT>& messenger) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "raybudget";
  app.pEngineName = "raybudget";
  app.apiVersion = VK_API_VERSION_1_3;
  std::vector<const char*> layers, extensions;
  VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  dbg.pfnUserCallback = onDebugMessage;
  dbg.pUserData = self;
  const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  features.pNext = &dbg;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  if (validation) {
    if (!hasLayer(kValidationLayer))
      throw Error("validation was requested but VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    ci.pNext = &features;
  }
  ci.enabledLayerCount = uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = uint32_t(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  VK_CHECK(vkCreateInstance(&ci, nullptr, &instance));
  Owned<VkInstance> owned(instance, [](VkInstance i) { vkDestroyInstance(i, nullptr); });
  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (!create || !destroy) throw Error("vkCreateDebugUtilsMessengerEXT is unavailable although validation is on");
    dbg.pNext = nullptr;
    VkDebugUtilsMessengerEXT m = VK_NULL_HANDLE;
    VK_CHECK(create(instance, &dbg, nullptr, &m));
    messenger = Owned<VkDebugUtilsMessengerEXT>(m, [instance, destroy](VkDebugUtilsMessengerEXT h) { destroy(instance, h, nullptr); });
  }
  return owned;
}

}  // namespace

Context::Context(const ContextOptions& options) : validation_(options.validation) {
  instance_ = createInstance(options.validation, this, messenger_);

  // Device choice: the named one, else the best type (discrete > integrated > virtual > CPU).
  std::vector<VkPhysicalDevice> devices = physicalDevices(instance_);
  if (devices.empty()) throw Error("no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");
  std::vector<std::pair<int, VkPhysicalDevice>> ranked;
  std::string names;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    names += std::string(names.empty() ? "" : ", ") + p.deviceName;
    if (!options.deviceName.empty() && std::string(p.deviceName).find(options.deviceName) == std::string::npos) continue;
    if (p.apiVersion < VK_API_VERSION_1_3) continue;
    ranked.push_back({typeRank(p.deviceType), d});
  }
  if (ranked.empty())
    throw Error("no Vulkan 1.3 device" + (options.deviceName.empty() ? std::string() : " matching '" + options.deviceName + "'") +
                " among: " + names);
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  physical_ = ranked.front().second;
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, families.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  auto family = std::find_if(families.begin(), families.end(),
                             [&](const VkQueueFamilyProperties& f) { return (f.queueFlags & need) == need && f.timestampValidBits > 0; });
  if (family == families.end()) throw Error(std::string(properties_.deviceName) + ": no graphics+compute queue with timestamps");
  queueFamily_ = uint32_t(family - families.begin());

  // Features we rely on: dynamic rendering and sync2 (1.3), bindless textures (1.2).
  VkPhysicalDeviceRayQueryFeaturesKHR fRq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR fAs{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  const std::vector<const char*> rayQueryExtensions = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME, VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                                       VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
  const bool rayQueryExts = std::all_of(rayQueryExtensions.begin(), rayQueryExtensions.end(),
                                        [&](const char* e) { return hasDeviceExtension(physical_, e); });
  fAs.pNext = &fRq;
  // The trace passes time each pixel's work with the subgroup clock (VK_KHR_shader_clock): what
  // the `benefit` policy learns each item's cost from (shaders/include/item_stats.glsl).
  if (!hasDeviceExtension(physical_, VK_KHR_SHADER_CLOCK_EXTENSION_NAME))
    throw Error(std::string(properties_.deviceName) + " lacks the required extension " VK_KHR_SHADER_CLOCK_EXTENSION_NAME);
  VkPhysicalDeviceShaderClockFeaturesKHR fClock{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_CLOCK_FEATURES_KHR};
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.pNext = &fClock;
  if (rayQueryExts) fClock.pNext = &fAs;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.pNext = &f13;
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f2.pNext = &f12;
  vkGetPhysicalDeviceFeatures2(physical_, &f2);
  auto require = [&](VkBool32 have, const char* name) {
    if (!have) throw Error(std::string(properties_.deviceName) + " lacks the required feature " + name);
  };
  require(f13.dynamicRendering, "dynamicRendering");
  require(f13.synchronization2, "synchronization2");
  require(f13.maintenance4, "maintenance4");  // glslang's SPIR-V 1.6 uses LocalSizeId
  require(f12.runtimeDescriptorArray, "runtimeDescriptorArray");
  require(f12.shaderSampledImageArrayNonUniformIndexing, "shaderSampledImageArrayNonUniformIndexing");
  require(f2.features.imageCubeArray, "imageCubeArray");
  require(fClock.shaderSubgroupClock, "shaderSubgroupClock");
  rayQuery_ = rayQueryExts && fRq.rayQuery && fAs.accelerationStructure && f12.bufferDeviceAddress;
  VkPhysicalDeviceRayQueryFeaturesKHR eRq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  eRq.rayQuery = VK_TRUE;
  VkPhysicalDeviceAccelerationStructureFeaturesKHR eAs{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  eAs.accelerationStructure = VK_TRUE;
  eAs.pNext = &eRq;
  VkPhysicalDeviceShaderClockFeaturesKHR eClock{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_CLOCK_FEATURES_KHR};
  eClock.shaderSubgroupClock = VK_TRUE;
  if (rayQuery_) eClock.pNext = &eAs;
  VkPhysicalDeviceVulkan13Features e13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  e13.pNext = &eClock;
  e13.dynamicRendering = VK_TRUE;
  e13.synchronization2 = VK_TRUE;
  e13.maintenance4 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features e12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  e12.pNext = &e13;
  e12.runtimeDescriptorArray = VK_TRUE;
  e12.shaderSampledImageArrayNonUniformIndexing = VK_TRUE;
  e12.hostQueryReset = f12.hostQueryReset;
  e12.bufferDeviceAddress = rayQuery_ ? VK_TRUE : VK_FALSE;
  VkPhysicalDeviceFeatures2 e2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  e2.pNext = &e12;
  e2.features.imageCubeArray = VK_TRUE;
  e2.features.samplerAnisotropy = f2.features.samplerAnisotropy;
  e2.features.shaderStorageImageWriteWithoutFormat = f2.features.shaderStorageImageWriteWithoutFormat;
  shaderFloat64_ = f2.features.shaderFloat64 == VK_TRUE;
  e2.features.shaderFloat64 = f2.features.shaderFloat64;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &e2;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  std::vector<const char*> extensions{VK_KHR_SHADER_CLOCK_EXTENSION_NAME};
  if (rayQuery_) extensions.insert(extensions.end(), rayQueryExtensions.begin(), rayQueryExtensions.end());
  dci.enabledExtensionCount = uint32_t(extensions.size());
  dci.ppEnabledExtensionNames = extensions.data();
  VkDevice device = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDevice(physical_, &dci, nullptr, &device));
  device_ = Owned<VkDevice>(device, [](VkDevice d) { vkDestroyDevice(d, nullptr); });
  vkGetDeviceQueue(device, queueFamily_, 0, &queue_);
  if (rayQuery_) {
    accel_ = loadAccelFunctions(device);
    VkPhysicalDeviceAccelerationStructurePropertiesKHR asProps{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    p2.pNext = &asProps;
    vkGetPhysicalDeviceProperties2(physical_, &p2);
    accelScratchAlignment_ = std::max<VkDeviceSize>(1, asProps.minAccelerationStructureScratchOffsetAlignment);
  }

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pci.queueFamilyIndex = queueFamily_;
  VkCommandPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateCommandPool(device, &pci, nullptr, &pool));
  uploadPool_ = Owned<VkCommandPool>(pool, [device](VkCommandPool p) { vkDestroyCommandPool(device, p, nullptr); });
}

Context::~Context() {
  if (device_) vkDeviceWaitIdle(device_);
}

uint32_t Context::memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & flags) == flags) return i;
  throw Error(std::string(properties_.deviceName) + ": no memory type with the needed properties");
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = uploadPool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateCommandBuffers(device_, &ai, &cmd));
  const VkDevice device = device_;
  const VkCommandPool pool = uploadPool_;
  Owned<VkCommandBuffer> owned(cmd, [device, pool](VkCommandBuffer c) { vkFreeCommandBuffers(device, pool, 1, &c); });
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
  record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  VK_CHECK(vkCreateFence(device_, &fci, nullptr, &fence));
  Owned<VkFence> ownedFence(fence, [device](VkFence f) { vkDestroyFence(device, f, nullptr); });
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  VK_CHECK(vkQueueSubmit(queue_, 1, &si, fence));
  VK_CHECK(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX));
}

std::vector<std::string> Context::validationMessages() const {
  std::lock_guard lock(messagesMutex_);
  return messages_;
}

void Context::recordValidationMessage(std::string message) {
  std::lock_guard lock(messagesMutex_);
  messages_.push_back(std::move(message));
}

std::vector<std::string> listDevices() {
  Owned<VkDebugUtilsMessengerEXT> unused;
  Owned<VkInstance> instance = createInstance(false, nullptr, unused);
  std::vector<std::string> out;
  for (VkPhysicalDevice d : physicalDevices(instance)) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    out.push_back(std::string(p.deviceName) + " (" + typeName(p.deviceType) + ", Vulkan " + std::to_string(VK_API_VERSION_MAJOR(p.apiVersion)) +
                  "." + std::to_string(VK_API_VERSION_MINOR(p.apiVersion)) + ")");
  }
  return out;
}

}  // namespace raybudget::vk
