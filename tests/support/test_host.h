// A host engine's Vulkan device, made the way docs/INTEGRATION.md tells a host to: its own
// instance with validation (synchronization validation on) and a messenger collecting
// every warning and error, a device made with raybudget::core::deviceSetup. Only the public
// API (raybudget/core.h) is used.
#pragma once
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "raybudget/core.h"

namespace raybudget::test {

class TestHost {
 public:
  TestHost();
  ~TestHost();
  TestHost(const TestHost&) = delete;
  TestHost& operator=(const TestHost&) = delete;

  core::HostDevice device() const;
  VkPhysicalDevice physicalDevice() const { return physical_; }
  const std::vector<std::string>& validationMessages() const { return messages_; }

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  core::DeviceSetup setup_;
  std::vector<std::string> messages_;
};

}  // namespace raybudget::test
