#include "vk/accel_functions.h"

#include <string>

#include "vk/check.h"

namespace raybudget::vk {

namespace {

template <typename Fn>
void load(PFN_vkGetDeviceProcAddr getProcAddr, VkDevice device, const char* name, Fn& out) {
  out = reinterpret_cast<Fn>(getProcAddr(device, name));
  if (!out) throw Error(std::string("the device enables VK_KHR_acceleration_structure but returns no ") + name);
}

}  // namespace

AccelFunctions loadAccelFunctions(PFN_vkGetDeviceProcAddr getProcAddr, VkDevice device) {
  AccelFunctions f;
  load(getProcAddr, device, "vkCreateAccelerationStructureKHR", f.create);
  load(getProcAddr, device, "vkDestroyAccelerationStructureKHR", f.destroy);
  load(getProcAddr, device, "vkGetAccelerationStructureBuildSizesKHR", f.buildSizes);
  load(getProcAddr, device, "vkCmdBuildAccelerationStructuresKHR", f.cmdBuild);
  load(getProcAddr, device, "vkGetAccelerationStructureDeviceAddressKHR", f.deviceAddress);
  return f;
}

}  // namespace raybudget::vk
