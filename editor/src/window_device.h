// The editor's window and Vulkan device: a GLFW window without a client API, an instance
// with the window system's surface extensions (and, with validation, the Khronos layer with
// synchronization validation, every message recorded), and a device made with what
// raybudget's core asks for (core::deviceSetup) plus VK_KHR_swapchain, on a queue family
// that renders, computes, times and presents to the window.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "owned.h"
#include "raybudget/core.h"

struct GLFWwindow;

namespace raybudget::editor {

class WindowDevice {
 public:
  WindowDevice(const std::string& title, uint32_t width, uint32_t height, bool validation, const std::string& deviceName);
  ~WindowDevice();
  WindowDevice(const WindowDevice&) = delete;
  WindowDevice& operator=(const WindowDevice&) = delete;

  GLFWwindow* window() const { return window_; }
  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return setup_.queueFamily; }
  VkSurfaceKHR surface() const { return surface_; }
  VkCommandPool commandPool() const { return pool_; }
  std::string deviceName() const;
  float timestampPeriodNs() const;
  core::HostDevice lend() const;
  // Memory for `req` of a type with `flags`; throws Error when the device has none.
  Owned<VkDeviceMemory> allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags flags) const;
  // The validation layer's messages so far (empty without validation).
  const std::vector<std::string>& validationMessages() const;

 private:
  GLFWwindow* window_ = nullptr;
  Owned<VkInstance> instance_;
  Owned<VkDebugUtilsMessengerEXT> messenger_;
  Owned<VkSurfaceKHR> surface_;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  core::DeviceSetup setup_;
  Owned<VkDevice> device_;
  VkQueue queue_ = VK_NULL_HANDLE;
  Owned<VkCommandPool> pool_;
  std::unique_ptr<std::vector<std::string>> messages_ = std::make_unique<std::vector<std::string>>();
};

// A buffer in host-visible, coherent memory, mapped for its lifetime.
struct HostBuffer {
  Owned<VkBuffer> buffer;
  Owned<VkDeviceMemory> memory;
  void* mapped = nullptr;
  VkDeviceSize size = 0;
};
HostBuffer createHostBuffer(const WindowDevice& wd, VkDeviceSize size, VkBufferUsageFlags usage);

// A device-local 2D image with a colour view.
struct DeviceImage {
  Owned<VkImage> image;
  Owned<VkDeviceMemory> memory;
  Owned<VkImageView> view;
  VkExtent2D extent{};
};
DeviceImage createImage(const WindowDevice& wd, VkFormat format, VkExtent2D extent, VkImageUsageFlags usage);

// One image layout transition (or memory dependency when the layouts are equal), colour aspect.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess, VkImageLayout from, VkImageLayout to);

}  // namespace raybudget::editor
