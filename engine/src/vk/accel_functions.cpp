#include "vk/accel_functions.h"

#include <string>

#include "vk/check.h"

namespace raybudget::vk {

namespace {

template <typename Fn>
void load(VkDevice device, const char* name, Fn& out) {
  out = reinterpret_cast<Fn>(vkGetDeviceProcAddr(device, name));
  if (!out) throw Error(std::string("the device enables VK_KHR_acceleration_structure but returns no ") + name);
}

}  // namespace

AccelFunctions loadAccelFunctions(VkDevice device) {
  AccelFunctions f;
  load(device, "vkCreateAccelerationStructureKHR", f.create);
  load(device, "vkDestroyAccelerationStructureKHR", f.destroy);
  load(device, "vkGetAccelerationStructureBuildSizesKHR", f.buildSizes);
  load(device, "vkCmdBuildAccelerationStructuresKHR", f.cmdBuild);
  load(device, "vkGetAccelerationStructureDeviceAddressKHR", f.deviceAddress);
  return f;
}

}  // namespace raybudget::vk
