// G-buffer pass: rasterises every visible object into depth, normal, base colour + metallic,
// roughness + transmission + IOR, emissive, object ID and material ID. Where glass shows the
// opaque frame behind it, it runs twice: the opaque draws, then, once that frame is lit, the
// transmissive draws over them.
#pragma once
#include <optional>

#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace raybudget::passes {

class GBufferPass {
 public:
  GBufferPass(const vk::Context& ctx, PassLayouts& layouts);
  enum class Draws { All, Opaque, Transmissive };
  // All and Opaque clear the G-buffer; Transmissive draws over it (after compute reads).
  void record(const FrameContext& fc, Draws draws = Draws::All) const;
  // The pixels [x0, x1) x [y0, y1) that the transmissive draws in view may show behind
  // them: their bounding spheres' screen rectangle grown by half its size on each side (the
  // refracted ray's offset, the blur), on even pixels; nothing when none is in view.
  static std::optional<glm::uvec4> transmissiveRect(const SceneGpu& scene, const glm::mat4& viewProj, uint32_t width, uint32_t height);
  // Whether any draw is transmissive: the frames may then show the opaque frame behind glass.
  static bool anyTransmissive(const SceneGpu& scene);

 private:
  const PassLayout& layout_;
  vk::Owned<VkPipeline> pipeline_;
};

}  // namespace raybudget::passes
