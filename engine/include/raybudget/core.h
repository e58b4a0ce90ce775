// raybudget's core, as a host engine uses it: what the library requires of a physical
// device, the features and extensions to enable on it, the host's handles it borrows (it
// never destroys them), and the Context that records a frame's budgeted ray-traced effects
// into the host's command buffer from the host's G-buffer. The standalone Renderer
// (raybudget/renderer.h) is a host of it like any other; docs/INTEGRATION.md walks through it.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "raybudget/camera.h"
#include "raybudget/scene.h"
#include "raybudget/settings.h"

namespace raybudget::testing {
struct Checks;
}

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
  VkImageView emissive = VK_NULL_HANDLE;       // R16G16B16A16_SFLOAT: emitted radiance rgb, a 1 where `layers` holds layers
  VkImageView objectId = VK_NULL_HANDLE;       // R32_UINT: the scene's object ID, 0xFFFFFFFF where none (clear to it)
  VkImageView materialId = VK_NULL_HANDLE;     // R32_UINT: the scene's material index
  // R32G32B32A32_SFLOAT: position xyz in render space (world minus Context::renderOrigin(),
  // which is zero for a scene within kRebaseDistance of the origin), and in w the geometric (triangle plane) normal
  // turned towards the camera, octahedron-encoded by packSnorm2x16 (secondary rays start at
  // the exact point and are offset along it: depth reconstruction is a few ulps off).
  VkImageView position = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;  // or GENERAL
  // Optional, R32G32B32A32_UINT: the material layers per pixel (docs/INTEGRATION.md; all zero:
  // none). Without it, each pixel's layers come from its material's factors, textures ignored.
  VkImageView layers = VK_NULL_HANDLE;
};

// The bits of FrameOutputs::tracedMask.
enum TracedEffect : uint32_t { kTracedShadows = 1u, kTracedReflections = 2u, kTracedRefractions = 4u };

// The renderer's results a host composes or shows, written by compute shaders and left in
// `layout`; the host orders its reads after them with a barrier from
// VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT / VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT.
struct FrameOutputs {
  VkImage hdr = VK_NULL_HANDLE, ldr = VK_NULL_HANDLE;              // R16G16B16A16_SFLOAT linear HDR; R8G8B8A8_UNORM tonemapped sRGB
  VkImageView hdrView = VK_NULL_HANDLE, ldrView = VK_NULL_HANDLE;
  // R16G16B16A16_SFLOAT, the terms hdr sums: the lit surface (direct light, emission, diffuse
  // ambient); its reflected light; its refracted light. Each is ray traced where tracedMask
  // says so and the raster fallback's elsewhere, so a host can keep one term and replace another.
  VkImage direct = VK_NULL_HANDLE, reflection = VK_NULL_HANDLE, refraction = VK_NULL_HANDLE;
  VkImageView directView = VK_NULL_HANDLE, reflectionView = VK_NULL_HANDLE, refractionView = VK_NULL_HANDLE;
  // R32_SFLOAT array, a layer per light (the first shadowVisibilityLayers; the image holds as
  // many more for the renderer's own use): the ray-traced visibility of each light where
  // shadows were traced this frame
  VkImage shadowVisibility = VK_NULL_HANDLE;
  uint32_t shadowVisibilityLayers = 0;
  // R32_UINT: per pixel, the effects whose rays were traced and shown there this frame
  // (TracedEffect bits); 0 where the raster fallbacks stand (and where a reduced ray rate
  // filled the pixel from traced neighbours).
  VkImage tracedMask = VK_NULL_HANDLE;
  VkImageView tracedMaskView = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};

// The images of the core's own G-buffer raster (recordFrame without a host G-buffer), in
// core::GBuffer's formats, SHADER_READ_ONLY_OPTIMAL after such a frame: for read-back.
// `layers` is 1x1 and not drawn where no material of the scene has layers (the emissive
// target's alpha is 0 on every pixel).
struct OwnGBuffer {
  VkImage depth, normal, baseMetal, roughTransIor, emissive, objectId, materialId, position, layers;
};

// The core on the host's device: the scene's buffers and acceleration structure, the
// selection, the raster fallbacks, the trace passes, lighting and compose.
class Context {
 public:
  // Uploads the scene and builds the acceleration structure, submitting to host.queue and
  // waiting. Throws raybudget::Error on bad settings or a failed Vulkan call.
  Context(const HostDevice& host, const Scene& scene, const RenderSettings& settings);
  // With the checks of raybudget/testing.h (tests).
  Context(const HostDevice& host, const Scene& scene, const RenderSettings& settings, const testing::Checks& checks);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Records one frame into `commandBuffer` (recording, outside a render pass): with
  // `gbuffer`, reading the host's; without, rasterising the scene into the core's own
  // (ownGBuffer()). Coverage, select, the raster fallbacks, the trace passes, lighting and
  // compose follow, into outputs(). Frames use two slots in turn: when the host records a
  // frame, the one it recorded two calls before must have completed on the GPU (the host
  // waited for its fence). A host G-buffer's writes must be visible to compute-shader reads
  // when the command buffer reaches this frame.
  void recordFrame(VkCommandBuffer commandBuffer, const Camera& camera, const GBuffer* gbuffer = nullptr);
  // Timings of frames whose slot has come round again (so they completed), each once, oldest
  // first; never waits. `everyRecordedFrameCompleted`: the host has waited for all of them,
  // so they are all returned.
  std::vector<FrameTiming> completedFrames(bool everyRecordedFrameCompleted = false);
  FrameOutputs outputs() const;
  OwnGBuffer ownGBuffer() const;
  uint64_t framesRecorded() const;

  // Switches policy and budget and forgets what the selection learned (Renderer's
  // restartSelection); every recorded frame has completed (collect their timings first with
  // completedFrames(true)). Throws Error on a bad budget.
  void restartSelection(Policy policy, float budgetMs, BenefitAblation ablation = BenefitAblation::None, ItemRate rate = ItemRate::Full);
  // T from the next recorded frame on, keeping what the selection learned (S, work per
  // pixel, the cost model). Throws Error on a bad budget.
  void setBudget(float budgetMs);
  CostModel costModel() const;
  void setCostModel(const CostModel& model);  // throws Error on negative or non-finite values
  // From the next frame on (the editor, animation), in world space; throws Error on a bad ID or
  // transform.
  void setObjectTransform(uint32_t objectId, const glm::mat4& transform);
  // The render space's origin in world space (raybudget::renderOrigin: the scene's centre
  // where that lies more than kRebaseDistance from the world's origin, else zero). The core
  // works in render space, world minus this origin; cameras and transforms are given in
  // world space, but a host G-buffer's positions must be in render space.
  glm::vec3 renderOrigin() const;
  // An object's K, Q and I from the next frame on (absent values derived as at load: K 1,
  // I 0.5, Q from its materials and the lights); S carries over. Throws Error naming the
  // object on a bad ID or a negative, non-finite or absurd value, and changes nothing then.
  void setObjectParams(uint32_t objectId, const RayBudgetParams& params);
  // The K, Q and I the selection uses for the object (all three filled in).
  RayBudgetParams objectParams(uint32_t objectId) const;
  // The per-object quantities of the last recorded frame, indexed by object ID; waits for
  // host.queue to be idle and copies them out. Needs RenderSettings::objectMetrics.
  std::vector<ObjectMetrics> objectMetrics() const;
  AccelStats accelStats() const;
  SceneEffects sceneEffects() const;  // what the scene can show at all
  // The device memory the core holds now, in bytes: its buffers and images (a fallback the scene
  // or the settings cannot use keeps its images at 1x1).
  uint64_t allocatedBytes() const;
  // The passes whose pipelines exist so far (built when a frame first needs them); the effects
  // pass's name says which paths its pipelines hold: trace_effects(reflections),
  // trace_effects(refractions) or trace_effects(reflections,refractions), "+fill" where it fills
  // reduced ray rates.
  std::vector<std::string> builtPipelines() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raybudget::core
