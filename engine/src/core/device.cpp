// raybudget/core.h's device functions: the requirements judged with every binding of
// bindings.h visible at once and one texture, an upper bound on any pass's layout (a scene's
// own texture count is checked when it loads).
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

namespace {

// Every unmet requirement in one message.
[[noreturn]] void refuse(const std::vector<std::string>& missing) {
  std::string text = "the Vulkan device cannot host raybudget:";
  for (const std::string& m : missing) text += "\n  " + m;
  throw Error(text);
}

}  // namespace

std::vector<DeviceReport> availableDevices() {
  std::vector<DeviceReport> out;
  for (vk::DeviceListing& d : vk::listDevices(passes::descriptorNeeds(1, false))) out.push_back({std::move(d.description), std::move(d.missing)});
  return out;
}

DeviceSetup deviceSetup(VkPhysicalDevice physicalDevice) {
  if (physicalDevice == VK_NULL_HANDLE) refuse(missingRequirements(physicalDevice));
  const vk::DeviceCapabilities caps = vk::queryCapabilities(physicalDevice);  // read once, judged and used
  const std::vector<std::string> missing = vk::missingRequirements(caps, passes::descriptorNeeds(1, false));
  if (!missing.empty()) refuse(missing);
  return vk::deviceSetup(caps);
}

}  // namespace raybudget::core
