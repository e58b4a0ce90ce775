// G-buffer pass: rasterises every visible object into depth, normal, base colour + metallic,
// roughness + transmission + IOR, emissive, object ID and material ID. Where glass shows the
// opaque frame behind it, it runs twice: the opaque draws, then, once that frame is lit, the
// transmissive draws over them.
#pragma once
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
  // Whether a transmissive draw is inside the view.
  static bool transmissiveInView(const SceneGpu& scene, const glm::mat4& viewProj);

 private:
  const PassLayout& layout_;
  vk::Owned<VkPipeline> pipeline_;
};

}  // namespace raybudget::passes
