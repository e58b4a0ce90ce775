// Raster fallback for reflections: cube maps of the scene captured from probe positions
// (raybudget::reflectionProbesOf) and GGX-prefiltered like the sky, which the fallback reads
// with parallax correction against each probe's box (shaders/include/environment.glsl). A
// probe is captured and prefiltered whole on the first frame; when an object inside its box
// moves it is captured again one cube face per frame, then prefiltered one roughness level
// per frame (12 frames; the fallback reads each level as it was until that level is
// replaced), so no frame pays a whole capture.
#pragma once
#include <vector>

#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "raybudget/scene.h"
#include "shared/types.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::passes {

class ReflectionProbePass {
 public:
  // `probes` in render space; `capture`: the tracer's probe_capture shader.
  ReflectionProbePass(const vk::Context& ctx, PassLayouts& layouts, std::vector<ReflectionProbe> probes, vk::Spirv capture);
  const std::vector<ReflectionProbe>& probes() const { return probes_; }
  // Whether its pipelines were built (on the first capture).
  bool built() const { return bool(capture_); }
  // Marks the probes whose box an object's bounding sphere meets before or after it moved.
  void objectMoved(const glm::vec4& before, const glm::vec4& after);
  bool anyStale() const;
  // Captures what is due (whole probes, or the next face of a recapture) and prefilters the
  // probes completed; how many were completed.
  uint32_t record(const FrameContext& fc);
  // Writes the probes' placement into the frame's uniforms (count 0 when `use` is false).
  void writeUniforms(gpu::FrameUniforms& u, bool use) const;
  // Before the first frame: both probe images into SHADER_READ_ONLY, so that every later
  // capture keeps the layers it does not write.
  static void initialize(VkCommandBuffer cmd, const FrameTargets& t);

 private:
  const vk::Context& ctx_;
  const PassLayout& layout_;
  vk::Spirv captureShader_;
  std::vector<ReflectionProbe> probes_;
  // Per probe: kCurrent; kWhole (not captured yet); the next face of a recapture (0..5), then
  // the next prefiltered level (kFirstLevel + level).
  static constexpr int kCurrent = -1, kWhole = -2, kFirstLevel = 6;
  std::vector<int> pending_;
  vk::Owned<VkPipeline> capture_;
  vk::Owned<VkPipeline> prefilter_;
};

}  // namespace raybudget::passes
