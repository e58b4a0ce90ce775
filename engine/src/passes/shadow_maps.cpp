#include "passes/shadow_maps.h"

#include <algorithm>
#include <cstddef>

#include <glm/geometric.hpp>

#include "shadow_frag.h"
#include "shadow_vert.h"
#include "shared/types.h"
#include "vk/pipelines.h"

namespace raybudget::passes {
namespace {

constexpr VkPipelineStageFlags2 kDepthStages = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
constexpr VkAccessFlags2 kDepthAccess = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;

}  // namespace

ShadowMapPass::ShadowMapPass(const vk::Context& ctx, PassLayouts& layouts, const ShadowViews& views, const FrameTargets& targets,
                             float slopeBias)
    : layout_(layouts.create({kSpirv_shadow_vert, kSpirv_shadow_frag})),
      stale_(views.mapLayers + 6 * views.pointCubes, true),
      resized_(views.mapLayers + views.pointCubes, false),
      slopeBias_(slopeBias) {
  for (uint32_t v = 0; v < views.mapLayers + views.pointCubes; ++v) full_.push_back(v < views.mapLayers ? targets.shadowMapSize : targets.cubeSize);
  size_ = full_;
  vk::GraphicsPipelineDesc d;
  d.vertex = kSpirv_shadow_vert;
  d.depthFormat = kDepthFormat;
  d.depthBias = true;
  opaque_ = vk::createGraphicsPipeline(ctx, layout_.pipelineLayout, d);
  d.fragment = kSpirv_shadow_frag;
  masked_ = vk::createGraphicsPipeline(ctx, layout_.pipelineLayout, d);
}

void ShadowMapPass::initialize(VkCommandBuffer cmd, const FrameTargets& t) {
  for (const vk::Image* img : {&t.shadowMaps, &t.pointShadows})
    vk::imageBarrier(cmd, *img, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                     VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

void ShadowMapPass::objectMoved(const ShadowViews& views, const glm::vec4& before, const glm::vec4& after) {
  auto sees = [&](const glm::mat4& viewProj) { return sphereInFrustum(viewProj, before) || sphereInFrustum(viewProj, after); };
  for (uint32_t l = 0; l < views.mapLayers; ++l)
    if (sees(views.mapViewProj[l])) stale_[l] = true;
  for (uint32_t f = 0; f < 6 * views.pointCubes; ++f)
    if (sees(views.cubeFaceViewProj[f])) stale_[views.mapLayers + f] = true;
}

uint32_t ShadowMapPass::neededSize(const glm::vec4& reach, uint32_t full, const glm::mat4& cameraViewProj, const glm::vec3& eye,
                                   float focalPixels) {
  if (reach.w < 0.0f) return full;
  if (!sphereInFrustum(cameraViewProj, reach)) return std::min(kMinSize, full);
  const float d = glm::length(glm::vec3(reach) - eye);
  if (d <= reach.w * 1.001f) return full;
  // The reach's diameter on screen, in pixels: 2 tan(angular radius) times the focal length.
  const float pixels = 2.0f * reach.w / std::sqrt(d * d - reach.w * reach.w) * focalPixels;
  uint32_t size = kMinSize;
  while (size < full && float(size) < pixels) size *= 2;
  return std::min(size, full);
}

void ShadowMapPass::fit(const ShadowViews& views, const glm::mat4& cameraViewProj, const glm::vec3& eye, float focalPixels) {
  for (uint32_t v = 0; v < size_.size(); ++v) {
    const uint32_t need = neededSize(views.fit[v].reach, full_[v], cameraViewProj, eye, focalPixels);
    uint32_t size = size_[v];
    if (!fitted_ || need > size) size = need;
    else if (4 * need <= size) size = 2 * need;
    if (size == size_[v]) continue;
    size_[v] = size;
    resized_[v] = true;
    if (v < views.mapLayers) stale_[v] = true;
    else std::fill_n(stale_.begin() + views.mapLayers + 6 * (v - views.mapLayers), 6, true);
  }
  fitted_ = true;
}

void ShadowMapPass::recordLightUpdates(const FrameContext& fc) {
  const ShadowViews& views = fc.scene.shadows;
  bool any = false;
  for (uint32_t v = 0; v < size_.size(); ++v) {
    if (!resized_[v]) continue;
    resized_[v] = false;
    any = true;
    // GpuLight's spotShadow.w and shadowParams.x are adjacent: one 8-byte update.
    const float share = float(size_[v]) / float(full_[v]);
    const float values[2] = {share, views.fit[v].fullSizeTexel / share};
    static_assert(offsetof(gpu::GpuLight, shadowParams) == offsetof(gpu::GpuLight, spotShadow) + 16);
    vkCmdUpdateBuffer(fc.cmd, fc.scene.lights.buffer, views.fit[v].light * sizeof(gpu::GpuLight) + offsetof(gpu::GpuLight, spotShadow) + 12,
                      sizeof(values), values);
  }
  // The frame-start barrier ordered the earlier frames' reads before the update.
  if (any)
    vk::memoryBarrier(fc.cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_UNIFORM_READ_BIT);
}

bool ShadowMapPass::anyStale() const { return std::find(stale_.begin(), stale_.end(), true) != stale_.end(); }

uint32_t ShadowMapPass::renderView(const FrameContext& fc, VkImageView view, uint32_t size, const glm::mat4& viewProj) const {
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {size, size}};
  ri.layerCount = 1;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(fc.cmd, &ri);
  const VkViewport viewport{0.0f, 0.0f, float(size), float(size), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {size, size}};
  VkPipeline bound = VK_NULL_HANDLE;
  uint32_t draws = 0;
  for (const Draw& d : fc.scene.draws) {
    if (!sphereInFrustum(viewProj, fc.scene.objectSpheres[d.object])) continue;
    ++draws;
    const VkPipeline want = d.alphaMask ? masked_.get() : opaque_.get();
    if (want != bound) {
      vkCmdBindPipeline(fc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, want);
      if (bound == VK_NULL_HANDLE) {
        layout_.bind(fc, VK_PIPELINE_BIND_POINT_GRAPHICS);
        vkCmdBindIndexBuffer(fc.cmd, fc.scene.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
      }
      vkCmdSetViewport(fc.cmd, 0, 1, &viewport);
      vkCmdSetScissor(fc.cmd, 0, 1, &scissor);
      // Slope-scaled bias against acne on surfaces at grazing angles to the light.
      vkCmdSetDepthBias(fc.cmd, 1.25f, 0.0f, slopeBias_);
      bound = want;
    }
    gpu::DrawPush push{};
    push.viewProj = viewProj;
    push.objectMaterial = glm::uvec4(d.object, d.material, 0, 0);
    layout_.push(fc, push);
    vkCmdDrawIndexed(fc.cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
  }
  vkCmdEndRendering(fc.cmd);
  return draws;
}

ShadowMapPass::Recorded ShadowMapPass::record(const FrameContext& fc) {
  const FrameTargets& t = fc.targets;
  const ShadowViews& views = fc.scene.shadows;
  recordLightUpdates(fc);
  std::vector<const vk::Image*> rendered;
  if (views.mapLayers > 0) rendered.push_back(&t.shadowMaps);
  if (views.pointCubes > 0) rendered.push_back(&t.pointShadows);
  // From SHADER_READ_ONLY, not UNDEFINED: the views that stay current keep their depths.
  for (const vk::Image* img : rendered)
    vk::imageBarrier(fc.cmd, *img, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0, kDepthStages, kDepthAccess,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  Recorded out;
  auto render = [&](VkImageView view, uint32_t size, const glm::mat4& viewProj) {
    out.draws += renderView(fc, view, size, viewProj);
    out.texels += size * size;
    ++out.views;
  };
  for (uint32_t l = 0; l < views.mapLayers; ++l)
    if (stale_[l]) render(t.shadowMapLayers[l], size_[l], views.mapViewProj[l]);
  for (uint32_t f = 0; f < 6 * views.pointCubes; ++f)
    if (stale_[views.mapLayers + f]) render(t.pointShadowFaces[f], size_[views.mapLayers + f / 6], views.cubeFaceViewProj[f]);
  for (const vk::Image* img : rendered)
    vk::imageBarrier(fc.cmd, *img, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  std::fill(stale_.begin(), stale_.end(), false);
  return out;
}

}  // namespace raybudget::passes
