// The device memory this process uses, as the driver reports it (VK_EXT_memory_budget).
#pragma once
#include <vulkan/vulkan.h>

#include "raybudget/renderer.h"

namespace raybudget::vk {

// Summed over the device's heaps; `known` is false where the device lacks the extension.
DeviceMemoryUsage memoryUsage(VkPhysicalDevice physicalDevice);

}  // namespace raybudget::vk
