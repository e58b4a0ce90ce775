// The standalone deferred renderer, a host of the core (raybudget/core.h) like any engine's:
// a Vulkan device of its own (or a host's), the frames' command buffers and fences, and the
// read-back of images; the core records the G-buffer raster, the raster fallbacks (shadow
// maps, environment map), the budgeted ray-traced effects, lighting, compose and tonemap,
// with a GPU timestamp bracket around every pass.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "raybudget/camera.h"
#include "raybudget/core.h"
#include "raybudget/scene.h"
#include "raybudget/settings.h"

namespace raybudget {

struct FrameImages {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> ldrRgba8;    // tonemapped sRGB
  std::vector<uint16_t> hdrRgba16;  // linear HDR, IEEE half floats
  std::vector<uint32_t> objectIds;  // G-buffer object IDs (RB_NO_OBJECT = 0xFFFFFFFF for none)
  // With readback(true): G-buffer world positions (xyz; w packs the geometric normal), the
  // ray-traced shadow mask (light-major: mask[light * pixels + pixel]), the materials, depth
  // and emission: the whole G-buffer in core::GBuffer's encoding.
  std::vector<float> positions;
  std::vector<uint16_t> normals;  // shading normals, RGBA half floats
  std::vector<float> shadowMask;
  std::vector<uint16_t> roughTransIor;  // roughness, transmission, IOR, unlit (RGBA half floats)
  std::vector<uint8_t> baseMetal;       // base colour and metallic (RGBA8 unorm)
  std::vector<float> depth;             // D32 depth, 0 near .. 1 far
  std::vector<uint16_t> emissive;       // emitted radiance (RGBA half floats)
  std::vector<uint32_t> materialIds;    // material index per pixel
  std::vector<uint32_t> tracedMask;     // core::FrameOutputs::tracedMask: the effects traced per pixel
};

// The device memory the process uses and the budget the driver gives it, summed over the
// device's heaps (VK_EXT_memory_budget; `known` is false where the device lacks it).
// `cpuDevice`: the device is the CPU (lavapipe), whose heaps are system memory: there the
// figures are the whole system's (they rise and fall with other processes) and the process's
// resident memory is the measure of what it holds.
struct DeviceMemoryUsage {
  uint64_t usedBytes = 0;
  uint64_t budgetBytes = 0;
  bool known = false;
  bool cpuDevice = false;
};

namespace testing {
struct Checks;
}

class Renderer {
 public:
  // On a device of its own (RenderSettings::device, ::validation).
  Renderer(const Scene& scene, const RenderSettings& settings);
  // On the host's device (raybudget/core.h): frames are submitted to host.queue from the
  // thread calling render(), readback() and finish(). (A host recording into its own
  // command buffers from its own G-buffer uses core::Context instead.)
  Renderer(const Scene& scene, const RenderSettings& settings, const core::HostDevice& host);
  // On its own device with the checks of raybudget/testing.h (tests).
  Renderer(const Scene& scene, const RenderSettings& settings, const testing::Checks& checks);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Records and submits one frame. Returns the timings of earlier frames whose results have
  // arrived meanwhile (read without waiting on the GPU for the frame just submitted).
  std::vector<FrameTiming> render(const Camera& camera);

  // Waits for every submitted frame and returns the timings not yet returned.
  std::vector<FrameTiming> finish();

  // Switches to another policy and budget and forgets what the selection learned (S, each
  // object's work per pixel) without rebuilding buffers and pipelines (benchmark sweeps).
  // The cost model's time scale (ms per unit of predicted work, a property of the device
  // and scene) is kept per cost unit: the paper's C and our work units each keep what they
  // last learned. With learnTimeScale off the next frames select exactly as a new Renderer
  // would. `rate`: RayTracingSettings::rate from now on. Finishes the frames in flight and
  // returns their timings. Throws Error on a bad budget.
  std::vector<FrameTiming> restartSelection(Policy policy, float budgetMs, BenefitAblation ablation = BenefitAblation::None,
                                            ItemRate rate = ItemRate::Full);

  // T from the next frame on, keeping what the selection learned (an engine adapting its
  // budget to its frame time). Throws Error on a bad budget.
  void setBudget(float budgetMs);
  // The cost model as learned so far (the current policy's unit included), and a way to
  // start from a saved one: a benchmark gives every configuration the same learned state,
  // so that its results do not depend on what ran before. setCostModel applies from the
  // next frame on; zero fields mean the prior. Throws Error on negative or non-finite values.
  CostModel costModel() const;
  void setCostModel(const CostModel& model);

  // Moves an object (animation, the editor): from the next frame on, its raster draws, its
  // BVH instance (only the TLAS is rebuilt) and its bounds follow. Throws Error on a bad
  // ID or transform.
  void setObjectTransform(uint32_t objectId, const glm::mat4& transform);
  // K, Q, I from the next frame on (core::Context::setObjectParams; the editor).
  void setObjectParams(uint32_t objectId, const RayBudgetParams& params);
  RayBudgetParams objectParams(uint32_t objectId) const;

  // The images of the last rendered frame (waits for it); `gbufferDetail` adds positions and
  // the shadow mask (for oracle tests).
  FrameImages readback(bool gbufferDetail = false);

  // The per-object quantities of the last rendered frame (waits for it), indexed by object
  // ID; needs RenderSettings::objectMetrics.
  std::vector<ObjectMetrics> objectMetrics();

  AccelStats accelStats() const;
  // The effects the scene can show at all (RayTracingSettings::maxRoughness applied).
  SceneEffects sceneEffects() const;
  // The passes whose pipelines exist so far (core::Context::builtPipelines: the effects pass by
  // the paths it holds, "+fill" its filling variant of reduced ray rates): pipelines are built
  // when a frame first needs them.
  std::vector<std::string> builtPipelines() const;
  std::string deviceName() const;
  DeviceMemoryUsage deviceMemoryUsage() const;
  // The device memory the renderer and its core hold now, in bytes (their own buffers and
  // images, whatever the driver reports).
  uint64_t allocatedBytes() const;
  std::vector<std::string> validationMessages() const;
  float aspect() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raybudget
