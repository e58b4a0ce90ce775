#include "window_device.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstring>

namespace raybudget::editor {
namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  const std::string text = data->pMessage ? data->pMessage : "";
  std::fprintf(stderr, "validation: %s\n", text.c_str());
  static_cast<std::vector<std::string>*>(user)->push_back(text);
  return VK_FALSE;
}

void onGlfwError(int code, const char* text) { std::fprintf(stderr, "glfw error %d: %s\n", code, text); }

bool hasLayer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const VkLayerProperties& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

}  // namespace

WindowDevice::WindowDevice(const std::string& title, uint32_t width, uint32_t height, bool validation, const std::string& deviceName) {
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit()) throw Error("editor: cannot open a window: GLFW found no display (set DISPLAY, or run under xvfb-run)");
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw Error("editor: GLFW finds no Vulkan loader");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw Error("editor: glfwCreateWindow failed");
  }

  uint32_t glfwCount = 0;
  const char** glfwExtensions = glfwGetRequiredInstanceExtensions(&glfwCount);
  std::vector<const char*> extensions(glfwExtensions, glfwExtensions + glfwCount);
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "raybudget-editor";
  app.apiVersion = VK_API_VERSION_1_3;
  VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  dbg.pfnUserCallback = onMessage;
  dbg.pUserData = messages_.get();
  const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  features.pNext = &dbg;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  if (validation) {
    if (!hasLayer(layer)) throw Error("editor: validation was requested but VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers)");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    ici.pNext = &features;
    ici.enabledLayerCount = 1;
    ici.ppEnabledLayerNames = &layer;
  }
  ici.enabledExtensionCount = uint32_t(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  check(vkCreateInstance(&ici, nullptr, &instance), "vkCreateInstance");
  instance_ = Owned<VkInstance>(instance, [](VkInstance i) { vkDestroyInstance(i, nullptr); });
  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    check(create(instance, &dbg, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
    messenger_ = Owned<VkDebugUtilsMessengerEXT>(messenger, [instance, destroy](VkDebugUtilsMessengerEXT m) { destroy(instance, m, nullptr); });
  }
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  check(glfwCreateWindowSurface(instance, window_, nullptr, &surface), "glfwCreateWindowSurface");
  surface_ = Owned<VkSurfaceKHR>(surface, [instance](VkSurfaceKHR s) { vkDestroySurfaceKHR(instance, s, nullptr); });

  // The first device that can host raybudget and present to the window (and matches the name).
  uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
  std::string why;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    if (!deviceName.empty() && std::string(p.deviceName).find(deviceName) == std::string::npos) continue;
    const std::vector<std::string> missing = core::missingRequirements(d);
    if (!missing.empty()) {
      why += std::string("\n  ") + p.deviceName + ": " + missing.front();
      continue;
    }
    const core::DeviceSetup setup = core::deviceSetup(d);
    VkBool32 present = VK_FALSE;
    check(vkGetPhysicalDeviceSurfaceSupportKHR(d, setup.queueFamily, surface, &present), "vkGetPhysicalDeviceSurfaceSupportKHR");
    if (!present) {
      why += std::string("\n  ") + p.deviceName + ": its compute queue family cannot present to the window";
      continue;
    }
    physicalDevice_ = d;
    setup_ = setup;
    break;
  }
  if (!physicalDevice_) throw Error("editor: no Vulkan device can host raybudget and show the window" + why);

  std::vector<const char*> deviceExtensions = setup_.extensions;
  deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = setup_.queueFamily;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = setup_.chain();
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = uint32_t(deviceExtensions.size());
  dci.ppEnabledExtensionNames = deviceExtensions.data();
  VkDevice device = VK_NULL_HANDLE;
  check(vkCreateDevice(physicalDevice_, &dci, nullptr, &device), "vkCreateDevice");
  device_ = Owned<VkDevice>(device, [](VkDevice d) { vkDestroyDevice(d, nullptr); });
  vkGetDeviceQueue(device, setup_.queueFamily, 0, &queue_);
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = setup_.queueFamily;
  pool_ = make(device, vkCreateCommandPool, vkDestroyCommandPool, pci, "vkCreateCommandPool");
}

WindowDevice::~WindowDevice() {
  if (device_) vkDeviceWaitIdle(device_);
  pool_.reset();
  device_.reset();
  surface_.reset();
  messenger_.reset();
  instance_.reset();
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

std::string WindowDevice::deviceName() const {
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(physicalDevice_, &p);
  return p.deviceName;
}

float WindowDevice::timestampPeriodNs() const {
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(physicalDevice_, &p);
  return p.limits.timestampPeriod;
}

core::HostDevice WindowDevice::lend() const {
  return {instance_, physicalDevice_, device_, setup_.queueFamily, queue_, vkGetDeviceProcAddr, setup_.rayQueryEnabled, setup_.shaderFloat64Enabled};
}

Owned<VkDeviceMemory> WindowDevice::allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags flags) const {
  VkPhysicalDeviceMemoryProperties p;
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &p);
  uint32_t type = 0;
  while (type < p.memoryTypeCount && !((req.memoryTypeBits & (1u << type)) && (p.memoryTypes[type].propertyFlags & flags) == flags)) ++type;
  if (type == p.memoryTypeCount) throw Error("editor: no suitable memory type");
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = type;
  return make(device(), vkAllocateMemory, vkFreeMemory, ai, "vkAllocateMemory");
}

const std::vector<std::string>& WindowDevice::validationMessages() const { return *messages_; }

HostBuffer createHostBuffer(const WindowDevice& wd, VkDeviceSize size, VkBufferUsageFlags usage) {
  HostBuffer b;
  b.size = size;
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = size;
  ci.usage = usage;
  b.buffer = make(wd.device(), vkCreateBuffer, vkDestroyBuffer, ci, "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(wd.device(), b.buffer, &req);
  b.memory = wd.allocate(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  check(vkBindBufferMemory(wd.device(), b.buffer, b.memory, 0), "vkBindBufferMemory");
  check(vkMapMemory(wd.device(), b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
  return b;
}

DeviceImage createImage(const WindowDevice& wd, VkFormat format, VkExtent2D extent, VkImageUsageFlags usage) {
  DeviceImage img;
  img.extent = extent;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {extent.width, extent.height, 1};
  ci.mipLevels = ci.arrayLayers = 1;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.usage = usage;
  img.image = make(wd.device(), vkCreateImage, vkDestroyImage, ci, "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(wd.device(), img.image, &req);
  img.memory = wd.allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  check(vkBindImageMemory(wd.device(), img.image, img.memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = img.image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = format;
  vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  img.view = make(wd.device(), vkCreateImageView, vkDestroyImageView, vi, "vkCreateImageView");
  return img;
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess, VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace raybudget::editor
