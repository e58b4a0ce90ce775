// raybudget/core.h's device functions: the requirements judged on the shared descriptor
// set's layout with one texture (a scene's own texture count is checked when it loads).
#include "passes/descriptors.h"
#include "raybudget/core.h"
#include "raybudget/error.h"
#include "vk/context.h"
#include "vk/device_requirements.h"

namespace raybudget::core {

std::vector<std::string> missingRequirements(VkPhysicalDevice physicalDevice) {
  if (physicalDevice == VK_NULL_HANDLE) return {"no physical device (VK_NULL_HANDLE)"};
  return vk::missingRequirements(vk::queryCapabilities(physicalDevice), passes::descriptorNeeds(1, false));
}

std::vector<DeviceReport> availableDevices() {
  std::vector<DeviceReport> out;
  for (vk::DeviceListing& d : vk::listDevices(passes::descriptorNeeds(1, false))) out.push_back({std::move(d.description), std::move(d.missing)});
  return out;
}

DeviceSetup deviceSetup(VkPhysicalDevice physicalDevice) {
  const std::vector<std::string> missing = missingRequirements(physicalDevice);
  if (!missing.empty()) {
    std::string text = "the Vulkan device cannot host raybudget:";
    for (const std::string& m : missing) text += "\n  " + m;
    throw Error(text);
  }
  return vk::deviceSetup(vk::queryCapabilities(physicalDevice));
}

}  // namespace raybudget::core
