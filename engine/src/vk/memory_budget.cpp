#include "vk/memory_budget.h"

#include <algorithm>

#include "vk/device_requirements.h"

namespace raybudget::vk {

DeviceMemoryUsage memoryUsage(VkPhysicalDevice physicalDevice) {
  const std::vector<std::string> extensions = extensionNames(physicalDevice);
  const bool supported = std::find(extensions.begin(), extensions.end(), VK_EXT_MEMORY_BUDGET_EXTENSION_NAME) != extensions.end();
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
