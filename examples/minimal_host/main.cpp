// minimal_host: an application with its own Vulkan device and its own G-buffer raster that
// lends both to raybudget.   minimal_host SCENE.gltf [--validation]
// It checks that its device can host raybudget (core::missingRequirements), creates it with
// the features raybudget asks for (core::deviceSetup), rasterises the scene's untextured,
// opaque materials into a G-buffer of its own in raybudget's encoding (gbuffer.frag), has
// raybudget's core record the ray-traced frame into its command buffer (core::Context),
// copies the composed image out and writes minimal_host.png into the working directory.
// With --validation its instance runs the Khronos layer and the program fails on any message.
// host.h holds what any engine already has (device, memory, images); this file, the meeting.
#include <glm/gtc/matrix_inverse.hpp>

#include "gbuffer_frag.h"
#include "gbuffer_vert.h"
#include "host.h"
#include "raybudget/image_io.h"

namespace {

using minimal_host::barrier;
using minimal_host::check;
using minimal_host::Host;

// What the G-buffer shaders take per draw (gbuffer.vert's push block), a draw, a vertex.
struct DrawPush {
  glm::mat4 viewProj;
  glm::vec4 baseColor, material, emissiveUnlit;
  glm::uvec4 ids;
  glm::vec4 camera;
};
struct Draw {
  uint32_t firstIndex, indexCount;
  DrawPush push;
};
struct WorldVertex {
  glm::vec3 position, normal;
  glm::vec4 color;
};

// The G-buffer raster pipeline: world-space vertices, seven colour targets and depth.
VkPipeline gbufferPipeline(Host& host, VkPipelineLayout layout, const VkFormat (&formats)[7], uint32_t w, uint32_t h) {
  VkShaderModule modules[2];
  const std::pair<const uint32_t*, size_t> code[2] = {{kSpirv_gbuffer_vert, sizeof(kSpirv_gbuffer_vert)},
                                                      {kSpirv_gbuffer_frag, sizeof(kSpirv_gbuffer_frag)}};
  VkPipelineShaderStageCreateInfo stages[2];
  for (int i = 0; i < 2; ++i) {
    const VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, code[i].second, code[i].first};
    check(vkCreateShaderModule(host.device, &mi, nullptr, &modules[i]), "vkCreateShaderModule");
    stages[i] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, i ? VK_SHADER_STAGE_FRAGMENT_BIT : VK_SHADER_STAGE_VERTEX_BIT,
                 modules[i], "main"};
  }
  const VkVertexInputBindingDescription binding{0, sizeof(WorldVertex), VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription attributes[] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(WorldVertex, position)},
                                                          {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(WorldVertex, normal)},
                                                          {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(WorldVertex, color)}};
  const VkPipelineVertexInputStateCreateInfo input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO, nullptr, 0, 1, &binding, 3, attributes};
  const VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO, nullptr, 0,
                                                        VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
  const VkViewport viewport{0.0f, 0.0f, float(w), float(h), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {w, h}};
  const VkPipelineViewportStateCreateInfo viewportState{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO, nullptr, 0, 1, &viewport, 1, &scissor};
  // Two-sided materials: no culling (glTF's fronts are counter-clockwise).
  const VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO, nullptr, 0, VK_FALSE, VK_FALSE,
                                                      VK_POLYGON_MODE_FILL, VK_CULL_MODE_NONE, VK_FRONT_FACE_COUNTER_CLOCKWISE, VK_FALSE, 0.0f, 0.0f,
                                                      0.0f, 1.0f};
  const VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO, nullptr, 0, VK_SAMPLE_COUNT_1_BIT};
  const VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO, nullptr, 0, VK_TRUE, VK_TRUE,
                                                    VK_COMPARE_OP_LESS};
  VkPipelineColorBlendAttachmentState blends[7] = {};
  for (auto& b : blends) b.colorWriteMask = 0xF;
  const VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO, nullptr, 0, VK_FALSE, VK_LOGIC_OP_CLEAR, 7,
                                                  blends};
  const VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO, nullptr, 0, 7, formats, VK_FORMAT_D32_SFLOAT};
  const VkGraphicsPipelineCreateInfo pci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering, 0, 2, stages, &input, &assembly, nullptr,
                                         &viewportState, &raster, &multisample, &depth, &blend, nullptr, layout};
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(vkCreateGraphicsPipelines(host.device, VK_NULL_HANDLE, 1, &pci, nullptr, &pipeline), "vkCreateGraphicsPipelines");
  for (VkShaderModule m : modules) vkDestroyShaderModule(host.device, m, nullptr);
  host.cleanup.push_back([&host, pipeline] { vkDestroyPipeline(host.device, pipeline, nullptr); });
  return pipeline;
}

// The host's geometry: each object's vertices in render space, one draw per primitive.
void buildDraws(const raybudget::Scene& scene, const glm::vec3& origin, const glm::mat4& viewProj, const glm::vec3& eye,
                std::vector<WorldVertex>& vertices, std::vector<uint32_t>& indices, std::vector<Draw>& draws) {
  for (const raybudget::Object& o : scene.objects) {
    const raybudget::Mesh& mesh = scene.meshes[o.mesh];
    const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(o.transform));
    const glm::mat4 model = raybudget::inRenderSpace(o.transform, origin);
    const uint32_t base = uint32_t(vertices.size());
    for (const raybudget::Vertex& v : mesh.vertices) vertices.push_back({glm::vec3(model * glm::vec4(v.position, 1.0f)), normalMatrix * v.normal, v.color});
    for (const raybudget::Primitive& p : mesh.primitives) {
      const raybudget::Material m = p.material >= 0 ? scene.materials[size_t(p.material)] : raybudget::Material{};
      draws.push_back({uint32_t(indices.size()), p.indexCount,
                       {viewProj, m.baseColorFactor, {m.metallic, m.roughness, m.transmission, m.ior}, {m.emissive, m.unlit ? 1.0f : 0.0f},
                        {o.id, uint32_t(std::max(p.material, 0)), m.doubleSided ? 1u : 0u, 0u}, glm::vec4(eye, 1.0f)}});
      for (uint32_t i = 0; i < p.indexCount; ++i) indices.push_back(base + mesh.indices[p.firstIndex + i]);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: minimal_host SCENE.gltf [--validation]\n");
    return 2;
  }
  const bool validation = argc > 2 && std::strcmp(argv[2], "--validation") == 0;
  try {
    Host host(validation);
    const raybudget::Scene scene = raybudget::loadScene(argv[1]);
    raybudget::RenderSettings settings;
    settings.width = 320;
    settings.height = 180;
    settings.policy = raybudget::Policy::All;  // every object's shadows, reflections, refractions traced
    const uint32_t w = settings.width, h = settings.height;
    {
      // The core borrows the device: it must be gone before the device is destroyed.
      raybudget::core::Context core(host.lend(), scene, settings);
      const float aspect = float(w) / float(h);
      const raybudget::Camera camera = raybudget::defaultCamera(scene, aspect);
      // The G-buffer holds positions in the core's render space (world minus its origin).
      const glm::vec3 origin = core.renderOrigin();
      const raybudget::Camera rendered = raybudget::inRenderSpace(camera, origin);
      std::vector<WorldVertex> vertices;
      std::vector<uint32_t> indices;
      std::vector<Draw> draws;
      buildDraws(scene, origin, rendered.projection(aspect) * rendered.view(), rendered.position, vertices, indices, draws);
      const VkBuffer vertexBuffer = host.buffer(vertices.size() * sizeof(WorldVertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, vertices.data()).first;
      const VkBuffer indexBuffer = host.buffer(indices.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, indices.data()).first;

      // The G-buffer in raybudget's encoding (core::GBuffer): seven colour planes and depth.
      const VkFormat formats[7] = {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT,
                                   VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32_UINT,      VK_FORMAT_R32_UINT,
                                   VK_FORMAT_R32G32B32A32_SFLOAT};  // normal .. materialId, position
      std::pair<VkImage, VkImageView> colors[7];
      for (int i = 0; i < 7; ++i) colors[i] = host.image(formats[i], w, h);
      const auto [depthImage, depthView] = host.image(VK_FORMAT_D32_SFLOAT, w, h);
      const VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawPush)};
      const VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 0, nullptr, 1, &range};
      VkPipelineLayout layout = VK_NULL_HANDLE;
      check(vkCreatePipelineLayout(host.device, &lci, nullptr, &layout), "vkCreatePipelineLayout");
      host.cleanup.push_back([&host, layout] { vkDestroyPipelineLayout(host.device, layout, nullptr); });
      const VkPipeline pipeline = gbufferPipeline(host, layout, formats, w, h);

      // One frame: the host's raster, raybudget's frame, the composed image copied out.
      const auto [readback, pixels] = host.buffer(VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
      const VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, host.setup.queueFamily};
      VkCommandPool pool = VK_NULL_HANDLE;
      check(vkCreateCommandPool(host.device, &pci, nullptr, &pool), "vkCreateCommandPool");
      host.cleanup.push_back([&host, pool] { vkDestroyCommandPool(host.device, pool, nullptr); });
      const VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool, VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
      VkCommandBuffer cmd = VK_NULL_HANDLE;
      check(vkAllocateCommandBuffers(host.device, &cai, &cmd), "vkAllocateCommandBuffers");
      const VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr, VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
      check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
      VkRenderingAttachmentInfo attachments[7];
      for (int i = 0; i < 7; ++i) {
        barrier(cmd, colors[i].first, false, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        attachments[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, nullptr, colors[i].second, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                          VK_RESOLVE_MODE_NONE, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE};
        if (formats[i] == VK_FORMAT_R32_UINT) attachments[i].clearValue.color.uint32[0] = 0xFFFFFFFFu;  // no object
      }
      const VkPipelineStageFlags2 depthStages = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
      barrier(cmd, depthImage, true, VK_PIPELINE_STAGE_2_NONE, 0, depthStages,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
              VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
      VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, nullptr, depthView, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                                VK_RESOLVE_MODE_NONE, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                                VK_ATTACHMENT_STORE_OP_STORE};
      depthAttachment.clearValue.depthStencil = {1.0f, 0};
      const VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO, nullptr, 0, {{0, 0}, {w, h}}, 1, 0, 7, attachments, &depthAttachment};
      vkCmdBeginRendering(cmd, &ri);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
      const VkDeviceSize offset = 0;
      vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
      vkCmdBindIndexBuffer(cmd, indexBuffer, 0, VK_INDEX_TYPE_UINT32);
      for (const Draw& d : draws) {
        vkCmdPushConstants(cmd, layout, range.stageFlags, 0, sizeof(DrawPush), &d.push);
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, 0, 0);
      }
      vkCmdEndRendering(cmd);
      // raybudget reads the G-buffer in compute shaders, SHADER_READ_ONLY_OPTIMAL.
      for (const auto& c : colors)
        barrier(cmd, c.first, false, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
      barrier(cmd, depthImage, true, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
              VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
      const raybudget::core::GBuffer gbuffer{depthView,        colors[0].second, colors[1].second, colors[2].second, colors[3].second,
                                             colors[4].second, colors[5].second, colors[6].second, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      core.recordFrame(cmd, camera, &gbuffer);

      // The composed image (tonemapped sRGB, GENERAL) out to the host.
      const raybudget::core::FrameOutputs out = core.outputs();
      VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
      const VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO, nullptr, 0, 1, &mb};
      vkCmdPipelineBarrier2(cmd, &dep);
      const VkBufferImageCopy copy{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
      vkCmdCopyImageToBuffer(cmd, out.ldr, out.layout, readback, 1, &copy);
      mb = {VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
            VK_ACCESS_2_HOST_READ_BIT};
      vkCmdPipelineBarrier2(cmd, &dep);
      check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
      const VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO, nullptr, 0, nullptr, nullptr, 1, &cmd};
      check(vkQueueSubmit(host.queue, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
      check(vkQueueWaitIdle(host.queue), "vkQueueWaitIdle");
      const auto* bytes = static_cast<const uint8_t*>(pixels);
      raybudget::writePng("minimal_host.png", w, h, std::vector<uint8_t>(bytes, bytes + size_t(w) * h * 4));
    }
    host.release();
    for (const std::string& m : minimal_host::messages) std::fprintf(stderr, "validation: %s\n", m.c_str());
    if (!minimal_host::messages.empty()) return 1;
    std::printf("wrote minimal_host.png (%s)\n", validation ? "validation clean" : "validation off");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "minimal_host: %s\n", e.what());
    return 1;
  }
}
