// The Vulkan instance, device and queue raybudget renders with: its own (with the validation
// messenger that records every warning and error) or a host's, borrowed; and one-shot
// command submission for uploads.
#pragma once
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "raybudget/core.h"
#include "vk/accel_functions.h"
#include "vk/device_requirements.h"
#include "vk/owned.h"

namespace raybudget::vk {

struct ContextOptions {
  bool validation = false;  // VK_LAYER_KHRONOS_validation with synchronization validation
  std::string deviceName;   // substring of the device name; empty: discrete > integrated > CPU
  DescriptorNeeds descriptorNeeds;  // per-stage descriptors the device must allow
};

class Context {
 public:
  // Creates an instance and a device of its own.
  explicit Context(const ContextOptions& options);
  // Borrows the host's; destroys nothing of it and records no validation messages (the host's
  // instance has its own messenger).
  explicit Context(const core::HostDevice& host);
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  ~Context();

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  bool validationEnabled() const { return validation_; }
  bool ownsDevice() const { return bool(ownedDevice_); }

  // VK_KHR_ray_query with acceleration structures and buffer device addresses: enabled
  // whenever the device offers them (lavapipe from Mesa 24+, current GPUs).
  bool rayQuerySupported() const { return rayQuery_; }
  // 64-bit floats in shaders, enabled where offered: the GPU selection divides through them
  // to get correctly rounded float quotients (select_common.glsl's exactQuotient).
  bool shaderFloat64() const { return shaderFloat64_; }
  const AccelFunctions& accel() const { return accel_; }
  VkDeviceSize accelScratchAlignment() const { return accelScratchAlignment_; }

  // Index of a memory type with `flags` among `typeBits`; throws when there is none.
  uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const;

  // Device memory allocated through this context and not yet freed (vk/resources.h's
  // buffers and images), in bytes; `counter` is what each allocation adds to and subtracts
  // from (shared, so memory freed after the context still counts down safely).
  uint64_t allocatedBytes() const { return *allocated_; }
  std::shared_ptr<std::atomic<uint64_t>> allocationCounter() const { return allocated_; }

  // Records `record` into a fresh command buffer, submits it and waits (uploads, set-up).
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

  // Validation-layer messages (warnings and errors) since start; tests require none.
  std::vector<std::string> validationMessages() const;
  void recordValidationMessage(std::string message);

 private:
  void finishSetup();  // properties, extension entry points, the upload pool

  bool validation_ = false;
  bool rayQuery_ = false;
  bool shaderFloat64_ = false;
  AccelFunctions accel_;
  VkDeviceSize accelScratchAlignment_ = 1;
  PFN_vkGetDeviceProcAddr getDeviceProcAddr_ = vkGetDeviceProcAddr;
  Owned<VkInstance> ownedInstance_;
  Owned<VkDebugUtilsMessengerEXT> messenger_;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  uint32_t queueFamily_ = 0;
  Owned<VkDevice> ownedDevice_;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  Owned<VkCommandPool> uploadPool_;
  std::shared_ptr<std::atomic<uint64_t>> allocated_ = std::make_shared<std::atomic<uint64_t>>(0);
  mutable std::mutex messagesMutex_;
  std::vector<std::string> messages_;
};

// The Vulkan devices this machine offers (name, type, version) and what each lacks.
struct DeviceListing {
  std::string description;
  std::vector<std::string> missing;
};
std::vector<DeviceListing> listDevices(const DescriptorNeeds& needs);

}  // namespace raybudget::vk
