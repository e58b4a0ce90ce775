#include "passes/gbuffer.h"

#include <algorithm>

#include "gbuffer_frag.h"
#include "gbuffer_vert.h"
#include "shared/config.h"
#include "shared/types.h"
#include "vk/pipelines.h"

namespace raybudget::passes {

GBufferPass::GBufferPass(const vk::Context& ctx, PassLayouts& layouts) : layout_(layouts.create({kSpirv_gbuffer_vert, kSpirv_gbuffer_frag})) {
  vk::GraphicsPipelineDesc d;
  d.vertex = kSpirv_gbuffer_vert;
  d.fragment = kSpirv_gbuffer_frag;
  d.colorFormats = {kNormalFormat, kBaseMetalFormat, kRoughTransIorFormat, kEmissiveFormat, kIdFormat, kIdFormat, kPositionFormat, kLayersFormat};
  d.depthFormat = kDepthFormat;
  pipeline_ = vk::createGraphicsPipeline(ctx, layout_.pipelineLayout, d);
}

bool GBufferPass::anyTransmissive(const SceneGpu& scene) {
  return std::any_of(scene.draws.begin(), scene.draws.end(), [](const Draw& d) { return d.transmissive; });
}

std::optional<glm::uvec4> GBufferPass::transmissiveRect(const SceneGpu& scene, const glm::mat4& viewProj, uint32_t width, uint32_t height) {
  glm::vec2 lo(1e30f), hi(-1e30f);
  bool any = false;
  for (const Draw& d : scene.draws) {
    const glm::vec4& s = scene.objectSpheres[d.object];
    if (!d.transmissive || !sphereInFrustum(viewProj, s)) continue;
    any = true;
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner = glm::vec3(s) + s.w * glm::vec3((c & 1) ? 1.0f : -1.0f, (c & 2) ? 1.0f : -1.0f, (c & 4) ? 1.0f : -1.0f);
      const glm::vec4 clip = viewProj * glm::vec4(corner, 1.0f);
      if (clip.w <= 1e-4f) return glm::uvec4(0, 0, width, height);  // around the camera: the whole frame
      const glm::vec2 ndc = glm::vec2(clip) / clip.w;
      lo = glm::min(lo, ndc);
      hi = glm::max(hi, ndc);
    }
  }
  if (!any) return std::nullopt;
  const glm::vec2 size = glm::vec2(float(width), float(height));
  glm::vec2 a = (lo * 0.5f + 0.5f) * size, b = (hi * 0.5f + 0.5f) * size;
  const glm::vec2 grow = 0.5f * (b - a) + 8.0f;
  a = glm::clamp(a - grow, glm::vec2(0.0f), size);
  b = glm::clamp(b + grow, glm::vec2(0.0f), size);
  const glm::uvec2 first = glm::uvec2(a) & ~1u, last = glm::uvec2(glm::ceil(b));
  if (last.x <= first.x || last.y <= first.y) return std::nullopt;
  return glm::uvec4(first, last);
}

void GBufferPass::record(const FrameContext& fc, Draws draws) const {
  const FrameTargets& t = fc.targets;
  // A fresh G-buffer discards the previous contents (UNDEFINED; the frame-start barrier
  // ordered any reads); the transmissive draws keep the opaque ones, after the compute
  // passes that read them.
  const bool over = draws == Draws::Transmissive;
  const VkImageLayout from = over ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED;
  const VkPipelineStageFlags2 after = over ? VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT : VK_PIPELINE_STAGE_2_NONE;
  for (const vk::Image* img : t.gbufferColors())
    vk::imageBarrier(fc.cmd, *img, after, 0, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, from,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  vk::imageBarrier(fc.cmd, t.depth, after, 0, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                   VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, from,
                   VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  const VkAttachmentLoadOp load = over ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;

  // Only the ID targets (object and material, RB_NO_OBJECT) and the depth are cleared: every
  // reader reads the other targets where the object ID names an object, whose draw wrote them. Not clearing five targets of
  // up to 16 bytes a pixel saves 2.5 ms of a 21 ms G-buffer at 1280x720 on lavapipe.
  // Without layered materials every pixel's emissive alpha says it has none, so nothing reads the
  // layers target: it is not drawn (1x1; 3 of AlphaBlendModeTest's 18 ms G-buffer at 1280x720).
  std::vector<VkRenderingAttachmentInfo> colors;
  for (const vk::Image* img : t.gbufferColors()) {
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = img == &t.layers && !t.needs.layers ? VkImageView(VK_NULL_HANDLE) : VkImageView(img->view);
    a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    a.loadOp = !over && img->desc.format != kIdFormat ? VK_ATTACHMENT_LOAD_OP_DONT_CARE : load;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    if (img->desc.format == kIdFormat) a.clearValue.color.uint32[0] = RB_NO_OBJECT;
    colors.push_back(a);
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = t.depth.view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = load;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {t.width, t.height}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = uint32_t(colors.size());
  ri.pColorAttachments = colors.data();
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(fc.cmd, &ri);
  vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  layout_.bind(fc, VK_PIPELINE_BIND_POINT_GRAPHICS);
  vkCmdBindIndexBuffer(fc.cmd, fc.scene.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
  const VkViewport viewport{0.0f, 0.0f, float(t.width), float(t.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {t.width, t.height}};
  vkCmdSetViewport(fc.cmd, 0, 1, &viewport);
  vkCmdSetScissor(fc.cmd, 0, 1, &scissor);
  for (const Draw& d : fc.scene.draws) {
    if ((draws == Draws::Opaque && d.transmissive) || (over && !d.transmissive)) continue;
    if (!sphereInFrustum(fc.viewProj, fc.scene.objectSpheres[d.object])) continue;
    gpu::DrawPush push{};
    push.objectMaterial = glm::uvec4(d.object, d.material, 0, 0);
    layout_.push(fc, push);
    vkCmdDrawIndexed(fc.cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
  }
  vkCmdEndRendering(fc.cmd);

  for (const vk::Image* img : t.gbufferColors())
    vk::imageBarrier(fc.cmd, *img, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  vk::imageBarrier(fc.cmd, t.depth, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

}  // namespace raybudget::passes
