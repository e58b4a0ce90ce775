// raybudget's boundary with a host engine's Vulkan device: what the library requires of a
// physical device, the features and extensions to enable on it, and the host's handles the
// library borrows (it never destroys them). The standalone Renderer runs on its own device
// or on a host's (Renderer's HostDevice constructor); docs/INTEGRATION.md walks through it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace raybudget::core {

// One sentence per thing `physicalDevice` lacks for raybudget (Vulkan version, extension,
// feature, limit, queue), naming it; empty when the device can host it. The native tracer's
// ray-query extensions are optional and never reported.
std::vector<std::string> missingRequirements(VkPhysicalDevice physicalDevice);

// The Vulkan devices this machine offers (name, type, Vulkan version), each with what it
// lacks (missingRequirements), from an instance of raybudget's own.
struct DeviceReport {
  std::string description;
  std::vector<std::string> missing;
};
std::vector<DeviceReport> availableDevices();

// What a host enables on its VkDevice: the required extensions and features, and the
// optional ones the device offers (VK_KHR_ray_query and acceleration structures for the
// native tracer, 64-bit floats for the exact GPU selection). A host may set more features in
// these structures, and chains its own structures through chain()'s argument.
struct DeviceSetup {
  std::vector<const char*> extensions;  // static strings
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan13Features vulkan13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceShaderClockFeaturesKHR shaderClock{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_CLOCK_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR accelerationStructure{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayQueryFeaturesKHR rayQuery{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  bool rayQueryEnabled = false;      // the native tracer's extensions and features are in the setup
  bool shaderFloat64Enabled = false;
  uint32_t queueFamily = 0;          // a graphics + compute family with timestamps

  // Links the structures (again, so a copied setup stays valid) and returns the head of the
  // chain for VkDeviceCreateInfo::pNext; `next` is appended after them.
  void* chain(void* next = nullptr);
};

// Throws raybudget::Error listing missingRequirements() when the device cannot host raybudget.
DeviceSetup deviceSetup(VkPhysicalDevice physicalDevice);

// The host's device, borrowed: raybudget never destroys these handles, and the host keeps
// them alive until the last raybudget object made from them is destroyed.
struct HostDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;  // created with deviceSetup(physicalDevice)
  uint32_t queueFamily = 0;          // graphics + compute with timestamps
  // Of queueFamily. Load-time uploads are submitted here and waited for; the host does not
  // use the queue from another thread meanwhile (Vulkan's external synchronisation).
  VkQueue queue = VK_NULL_HANDLE;
  PFN_vkGetDeviceProcAddr getDeviceProcAddr = nullptr;  // extension entry points come from it
  bool rayQueryEnabled = false;      // DeviceSetup::rayQueryEnabled of the setup the device was made with
  bool shaderFloat64Enabled = false; // DeviceSetup::shaderFloat64Enabled, likewise
};

// A G-buffer the host rasterised, of the renderer's size, in raybudget's encoding: the
// formats below, each view read by compute shaders in `layout` (docs/INTEGRATION.md).
struct GBuffer {
  VkImageView depth = VK_NULL_HANDLE;          // D32_SFLOAT, 0 near .. 1 far (clear to 1)
  VkImageView normal = VK_NULL_HANDLE;         // R16G16B16A16_SFLOAT: world shading normal, unit xyz
  VkImageView baseMetal = VK_NULL_HANDLE;      // R8G8B8A8_UNORM: base colour rgb (linear), metallic a
  VkImageView roughTransIor = VK_NULL_HANDLE;  // R16G16B16A16_SFLOAT: roughness, transmission, IOR, unlit (0/1)
  VkImageView emissive = VK_NULL_HANDLE;       // R16G16B16A16_SFLOAT: emitted radiance rgb
  VkImageView objectId = VK_NULL_HANDLE;       // R32_UINT: the scene's object ID, 0xFFFFFFFF where none (clear to it)
  VkImageView materialId = VK_NULL_HANDLE;     // R32_UINT: the scene's material index
  // R32G32B32A32_SFLOAT: world position xyz, and in w the geometric (triangle plane) normal
  // turned towards the camera, octahedron-encoded by packSnorm2x16 (secondary rays start at
  // the exact point and are offset along it: depth reconstruction is a few ulps off).
  VkImageView position = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;  // or GENERAL
};

// The renderer's results a host composes or shows, written by compute shaders and left in
// `layout`; the host orders its reads after them with a barrier from
// VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT / VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT.
struct FrameOutputs {
  VkImage hdr = VK_NULL_HANDLE, ldr = VK_NULL_HANDLE;              // R16G16B16A16_SFLOAT linear HDR; R8G8B8A8_UNORM tonemapped sRGB
  VkImageView hdrView = VK_NULL_HANDLE, ldrView = VK_NULL_HANDLE;
  VkImage direct = VK_NULL_HANDLE, indirect = VK_NULL_HANDLE;      // R16G16B16A16_SFLOAT: the lit surface, and its reflected + refracted light
  VkImageView directView = VK_NULL_HANDLE, indirectView = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};

}  // namespace raybudget::core
