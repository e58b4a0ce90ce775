// The ray tracer the trace passes query, chosen in one place (createSceneTracer): our
// compute BVH (bvh/, shaders/include/rayquery_compute.glsl) or the device's VK_KHR_ray_query
// acceleration structures (native_accel.h). It owns its structures, keeps them following
// moved objects, and says how the shaders reach it: the trace shaders' variant and the
// three tracer bindings (shaders/include/rayquery.glsl).
#pragma once
#include <memory>
#include <span>

#include "raybudget/renderer.h"
#include "raybudget/scene.h"
#include "shared/types.h"
#include "vk/context.h"
#include "vk/pipelines.h"
#include "vk/resources.h"

namespace raybudget::passes {

enum class TraceShader { Shadows, Effects, ReflectionProbe };

class SceneTracer {
 public:
  virtual ~SceneTracer() = default;
  virtual Tracer kind() const = 0;
  virtual AccelStats stats() const = 0;
  virtual vk::Spirv shader(TraceShader which) const = 0;
  // Points those of kBvhNodes, kBvhTriangles and kBvhInstances that are among `only`
  // (sorted: the set's bindings) at the structures, which live as long as the tracer.
  virtual void writeBindings(VkDevice device, VkDescriptorSet set, std::span<const uint32_t> only) const = 0;
  // Moved objects: brings the structures up to `shell`'s transforms (on the CPU, staged in
  // `staging`, grown as needed) and records their upload with the objects' new `records`
  // into `cmd`, then a barrier before every later read. Returns the CPU milliseconds.
  virtual double recordMovedObjects(VkCommandBuffer cmd, const Scene& shell, std::span<const gpu::GpuObject> records, vk::Buffer& staging,
                                    const vk::Buffer& objectRecords) = 0;
};

// `scene` with its geometry (the structures are built here and keep no vertex data).
std::unique_ptr<SceneTracer> createSceneTracer(const vk::Context& ctx, const Scene& scene, const RenderSettings& settings);

// The compute tracer's and the native one's, for createSceneTracer.
std::unique_ptr<SceneTracer> createComputeTracer(const vk::Context& ctx, const Scene& scene, SpatialSplits splits);
std::unique_ptr<SceneTracer> createNativeTracer(const vk::Context& ctx, const Scene& scene);

// Applies those of `writes` whose binding is among `only` (sorted).
void updateBindingsAmong(VkDevice device, std::span<const VkWriteDescriptorSet> writes, std::span<const uint32_t> only);

// The mapped bytes of `staging`, made host-visible and at least `bytes` long first.
uint8_t* stagingOf(const vk::Context& ctx, vk::Buffer& staging, VkDeviceSize bytes);

}  // namespace raybudget::passes
