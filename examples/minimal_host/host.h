// The host's side of minimal_host: what an engine has before it meets raybudget (an instance
// and a device that meet raybudget's requirements, memory, buffers, images, barriers).
#pragma once
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "raybudget/core.h"
#include "raybudget/error.h"

namespace minimal_host {

// The validation layer's messages (with --validation).
inline std::vector<std::string> messages;

inline VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  messages.push_back(data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

inline void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throw raybudget::Error(std::string(call) + " failed with VkResult " + std::to_string(int(result)));
}

// The host's instance and device, what an engine has before raybudget; everything made on
// the device registers its destruction in `cleanup`, run in reverse at the end.
struct Host {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  raybudget::core::DeviceSetup setup;
  std::vector<std::function<void()>> cleanup;

  explicit Host(bool validation) {
    const VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "minimal_host", 1, nullptr, 0, VK_API_VERSION_1_3};
    const VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT, nullptr, 0,
                                                 VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
                                                 VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT, onMessage};
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    const VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, validation ? &dbg : nullptr, 0, &app, validation ? 1u : 0u, &layer,
                                   validation ? 1u : 0u, &extension};
    check(vkCreateInstance(&ici, nullptr, &instance), "vkCreateInstance");
    if (validation) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
      check(create(instance, &dbg, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
      cleanup.push_back([this, destroy, messenger] { destroy(instance, messenger, nullptr); });
    }
    // The first device raybudget can run on; say why the others cannot.
    uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
    for (VkPhysicalDevice d : devices) {
      const std::vector<std::string> missing = raybudget::core::missingRequirements(d);
      for (const std::string& m : missing) std::fprintf(stderr, "skipping a device: %s\n", m.c_str());
      if (missing.empty() && !physicalDevice) physicalDevice = d;
    }
    if (!physicalDevice) throw raybudget::Error("no Vulkan device can host raybudget");
    // raybudget's features and extensions; an engine would chain its own after them.
    setup = raybudget::core::deviceSetup(physicalDevice);
    const float priority = 1.0f;
    const VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, setup.queueFamily, 1, &priority};
    const VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, setup.chain(), 0, 1, &qci, 0, nullptr, uint32_t(setup.extensions.size()),
                                 setup.extensions.data()};
    check(vkCreateDevice(physicalDevice, &dci, nullptr, &device), "vkCreateDevice");
    vkGetDeviceQueue(device, setup.queueFamily, 0, &queue);
  }

  // Destroys what was made on the device (its messages are still collected).
  void release() {
    if (device) vkDeviceWaitIdle(device);
    for (auto c = cleanup.rbegin(); c != cleanup.rend(); ++c) (*c)();
    cleanup.clear();
  }

  ~Host() {
    release();
    if (device) vkDestroyDevice(device, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
  }

  raybudget::core::HostDevice lend() const {
    return {instance, physicalDevice, device, setup.queueFamily, queue, vkGetDeviceProcAddr, setup.rayQueryEnabled, setup.shaderFloat64Enabled};
  }

  VkDeviceMemory allocate(VkMemoryRequirements req, VkMemoryPropertyFlags flags) {
    VkPhysicalDeviceMemoryProperties p;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &p);
    uint32_t type = 0;
    while (type < p.memoryTypeCount && !((req.memoryTypeBits & (1u << type)) && (p.memoryTypes[type].propertyFlags & flags) == flags)) ++type;
    if (type == p.memoryTypeCount) throw raybudget::Error("no suitable memory type");
    const VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(device, &ai, nullptr, &memory), "vkAllocateMemory");
    cleanup.push_back([this, memory] { vkFreeMemory(device, memory, nullptr); });
    return memory;
  }

  // A buffer in host-visible memory (an example's simplification), mapped.
  std::pair<VkBuffer, void*> buffer(VkDeviceSize size, VkBufferUsageFlags usage, const void* data = nullptr) {
    const VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, size, usage};
    VkBuffer buffer = VK_NULL_HANDLE;
    check(vkCreateBuffer(device, &ci, nullptr, &buffer), "vkCreateBuffer");
    cleanup.push_back([this, buffer] { vkDestroyBuffer(device, buffer, nullptr); });
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, buffer, &req);
    const VkDeviceMemory memory = allocate(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
    void* mapped = nullptr;
    check(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    if (data) std::memcpy(mapped, data, size);
    return {buffer, mapped};
  }

  // One G-buffer plane: a device-local image with its view.
  std::pair<VkImage, VkImageView> image(VkFormat format, uint32_t w, uint32_t h) {
    const bool depth = format == VK_FORMAT_D32_SFLOAT;
    const VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, nullptr, 0, VK_IMAGE_TYPE_2D, format, {w, h, 1}, 1, 1, VK_SAMPLE_COUNT_1_BIT,
                               VK_IMAGE_TILING_OPTIMAL,
                               VK_IMAGE_USAGE_SAMPLED_BIT | (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT)};
    VkImage image = VK_NULL_HANDLE;
    check(vkCreateImage(device, &ci, nullptr, &image), "vkCreateImage");
    cleanup.push_back([this, image] { vkDestroyImage(device, image, nullptr); });
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    check(vkBindImageMemory(device, image, allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), 0), "vkBindImageMemory");
    const VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, nullptr, 0, image, VK_IMAGE_VIEW_TYPE_2D, format, {},
                                   {VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1, 0, 1}};
    VkImageView view = VK_NULL_HANDLE;
    check(vkCreateImageView(device, &vi, nullptr, &view), "vkCreateImageView");
    cleanup.push_back([this, view] { vkDestroyImageView(device, view, nullptr); });
    return {image, view};
  }
};

// A layout transition of a colour or depth image between two synchronisation scopes.
inline void barrier(VkCommandBuffer cmd, VkImage image, bool depth, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
             VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, VkImageLayout from, VkImageLayout to) {
  const VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, nullptr, srcStage, srcAccess, dstStage, dstAccess, from, to,
                                VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, image,
                                {VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1, 0, 1}};
  const VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO, nullptr, 0, 0, nullptr, 0, nullptr, 1, &b};
  vkCmdPipelineBarrier2(cmd, &d);
}

}  // namespace minimal_host
