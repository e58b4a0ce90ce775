#include "vk/memory_budget.h"

#include <cstring>
#include <vector>

namespace raybudget::vk {

DeviceMemoryUsage memoryUsage(VkPhysicalDevice physicalDevice) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, extensions.data());
  bool supported = false;
  for (const VkExtensionProperties& e : extensions) supported = supported || std::strcmp(e.extensionName, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME) == 0;
  DeviceMemoryUsage usage;
  VkPhysicalDeviceProperties properties0;
  vkGetPhysicalDeviceProperties(physicalDevice, &properties0);
  usage.cpuDevice = properties0.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  if (!supported) return usage;
  VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
  VkPhysicalDeviceMemoryProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2, &budget};
  vkGetPhysicalDeviceMemoryProperties2(physicalDevice, &properties);
  for (uint32_t h = 0; h < properties.memoryProperties.memoryHeapCount; ++h) {
    usage.usedBytes += budget.heapUsage[h];
    usage.budgetBytes += budget.heapBudget[h];
  }
  usage.known = true;
  return usage;
}

}  // namespace raybudget::vk
