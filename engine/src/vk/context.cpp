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
  ownedInstance_ = createInstance(options.validation, this, messenger_);
  instance_ = ownedInstance_;

  // Device choice: the named one, else the best type (discrete > integrated > virtual > CPU)
  // among those that meet the requirements.
  std::vector<VkPhysicalDevice> devices = physicalDevices(instance_);
  if (devices.empty()) throw Error("no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");
  struct Candidate {
    int rank;
    VkPhysicalDevice device;
    DeviceCapabilities caps;
  };
  std::vector<Candidate> ranked;
  std::string names, reasons;
  for (VkPhysicalDevice d : devices) {
    const DeviceCapabilities caps = queryCapabilities(d);
    names += (names.empty() ? "" : ", ") + caps.name;
    if (!options.deviceName.empty() && caps.name.find(options.deviceName) == std::string::npos) continue;
    const std::vector<std::string> missing = missingRequirements(caps, options.descriptorNeeds);
    for (const std::string& m : missing) reasons += "\n  " + m;
    if (!missing.empty()) continue;
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    ranked.push_back({typeRank(p.deviceType), d, caps});
  }
  if (ranked.empty())
    throw Error("no Vulkan device" + (options.deviceName.empty() ? std::string() : " matching '" + options.deviceName + "'") +
                " can run raybudget (devices: " + names + ")" + reasons);
  std::stable_sort(ranked.begin(), ranked.end(), [](const Candidate& a, const Candidate& b) { return a.rank < b.rank; });
  physical_ = ranked.front().device;

  core::DeviceSetup setup = deviceSetup(ranked.front().caps);
  queueFamily_ = setup.queueFamily;
  rayQuery_ = setup.rayQueryEnabled;
  shaderFloat64_ = setup.shaderFloat64Enabled;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = setup.chain();
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = uint32_t(setup.extensions.size());
  dci.ppEnabledExtensionNames = setup.extensions.data();
  VkDevice device = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDevice(physical_, &dci, nullptr, &device));
  ownedDevice_ = Owned<VkDevice>(device, [](VkDevice d) { vkDestroyDevice(d, nullptr); });
  device_ = device;
  vkGetDeviceQueue(device, queueFamily_, 0, &queue_);
  finishSetup();
}

Context::Context(const core::HostDevice& host)
    : rayQuery_(host.rayQueryEnabled),
      shaderFloat64_(host.shaderFloat64Enabled),
      instance_(host.instance),
      physical_(host.physicalDevice),
      queueFamily_(host.queueFamily),
      device_(host.device),
      queue_(host.queue) {
  if (!host.instance || !host.physicalDevice || !host.device || !host.queue || !host.getDeviceProcAddr)
    throw Error("HostDevice: instance, physicalDevice, device, queue and getDeviceProcAddr must all be set");
  getDeviceProcAddr_ = host.getDeviceProcAddr;
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, nullptr);
  if (host.queueFamily >= familyCount)
    throw Error("HostDevice: queue family " + std::to_string(host.queueFamily) + " does not exist (the device has " + std::to_string(familyCount) + ")");
  finishSetup();
}

void Context::finishSetup() {
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
  if (rayQuery_) {
    accel_ = loadAccelFunctions(getDeviceProcAddr_, device_);
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
  const VkDevice device = device_;
  VK_CHECK(vkCreateCommandPool(device, &pci, nullptr, &pool));
  uploadPool_ = Owned<VkCommandPool>(pool, [device](VkCommandPool p) { vkDestroyCommandPool(device, p, nullptr); });
}

Context::~Context() {
  // A borrowed device's host waits for its own work; ours waits before it is destroyed.
  if (ownedDevice_) vkDeviceWaitIdle(device_);
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

std::vector<DeviceListing> listDevices(const DescriptorNeeds& needs) {
  Owned<VkDebugUtilsMessengerEXT> unused;
  Owned<VkInstance> instance = createInstance(false, nullptr, unused);
  std::vector<DeviceListing> out;
  for (VkPhysicalDevice d : physicalDevices(instance)) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    out.push_back({std::string(p.deviceName) + " (" + typeName(p.deviceType) + ", Vulkan " + std::to_string(VK_API_VERSION_MAJOR(p.apiVersion)) +
                       "." + std::to_string(VK_API_VERSION_MINOR(p.apiVersion)) + ")",
                   missingRequirements(queryCapabilities(d), needs)});
  }
  return out;
}

}  // namespace raybudget::vk
