// What raybudget needs of a physical device, as data: the capabilities a device offers are
// read once (queryCapabilities) and judged by a plain function, so that the judgement can be
// tested with made-up devices; the features and extensions to enable follow from the same
// capabilities (one list, for our own device and for a host's).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "raybudget/core.h"

namespace raybudget::vk {

struct DeviceCapabilities {
  std::string name;
  uint32_t apiVersion = 0;
  std::vector<std::string> extensions;
  VkPhysicalDeviceFeatures features{};
  VkPhysicalDeviceLimits limits{};
  bool dynamicRendering = false, synchronization2 = false, maintenance4 = false;
  bool runtimeDescriptorArray = false, sampledImageArrayNonUniformIndexing = false;
  bool bufferDeviceAddress = false, hostQueryReset = false;
  bool shaderSubgroupClock = false;
  bool shaderDeviceClock = false;
  bool rayQuery = false, accelerationStructure = false;
  std::optional<uint32_t> queueFamily;  // graphics + compute with timestamps
  bool hasExtension(const char* name) const;
};

// Descriptors one pipeline stage sees at once (the shared set is visible to every stage).
struct DescriptorNeeds {
  uint32_t storageBuffers = 0, uniformBuffers = 0, sampledImages = 0, storageImages = 0, samplers = 0;
};

DeviceCapabilities queryCapabilities(VkPhysicalDevice device);

// The device extensions the physical device offers.
std::vector<std::string> extensionNames(VkPhysicalDevice device);

// One line per unmet requirement, naming it and what the device has (empty: usable).
std::vector<std::string> missingRequirements(const DeviceCapabilities& caps, const DescriptorNeeds& needs);

// The native tracer's extensions and features are all offered (optional: the compute tracer
// needs none of them).
bool offersRayQuery(const DeviceCapabilities& caps);

// The extensions and features to enable: the required ones and the optional ones offered.
core::DeviceSetup deviceSetup(const DeviceCapabilities& caps);

}  // namespace raybudget::vk
