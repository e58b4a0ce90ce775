// Entry points of VK_KHR_acceleration_structure. The loader exports only core functions,
// so these come from vkGetDeviceProcAddr once the device exists.
#pragma once
#include <vulkan/vulkan.h>

namespace raybudget::vk {

struct AccelFunctions {
  PFN_vkCreateAccelerationStructureKHR create = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroy = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR buildSizes = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmdBuild = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR deviceAddress = nullptr;
};

// Loads every entry point; throws naming the first one the device does not return.
AccelFunctions loadAccelFunctions(PFN_vkGetDeviceProcAddr getProcAddr, VkDevice device);

}  // namespace raybudget::vk
