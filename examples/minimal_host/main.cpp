// minimal_host: an application with its own Vulkan device and its own G-buffer raster that
// lends both to raybudget.
//   minimal_host SCENE.gltf [--validation]
// It checks that its device can host raybudget (core::missingRequirements), creates it with
// the features raybudget asks for (core::deviceSetup), rasterises the scene's untextured,
// opaque materials into a G-buffer of its own in raybudget's encoding (gbuffer.frag), has
// raybudget's core record the ray-traced frame into its command buffer (core::Context),
// copies the composed image out and writes minimal_host.png into the working directory.
// With --validation its instance runs the Khronos layer and the program fails on any message.
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>
#include <vulkan/vulkan.h>

#include "gbuffer_frag.h"
#include "gbuffer_vert.h"
#include "raybudget/core.h"
#include "raybudget/error.h"
#include "raybudget/image_io.h"

namespace {

std::vector<std::string> messages;

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  messages.push_back(data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throw raybudget::Error(std::string(call) + " failed with VkResult " + std::to_string(int(result)));
}

// The host's instance and device, what an engine has before raybudget; everything made on
// the device registers its destruction in `cleanup`, run in reverse at the end.
struct Host {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  raybudget::core::DeviceSetup setup;
  std::vector<std::function<void()>> cleanup;

  explicit Host(bool validation) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "minimal_host", 1, nullptr, 0, VK_API_VERSION_1_3};
    VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    dbg.pfnUserCallback = onMessage;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, validation ? &dbg : nullptr, 0, &app, validation ? 1u : 0u, &layer,
                             validation ? 1u : 0u, &extension};
    check(vkCreateInstance(&ici, nullptr, &instance), "vkCreateInstance");
    if (validation) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
      VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
      check(create(instance, &dbg, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
      cleanup.push_back([this, messenger] {
        reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"))(instance, messenger,
                                                                                                                                  nullptr);
      });
    }
    // The first device raybudget can run on; say why the others cannot.
    uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
    for (VkPhysicalDevice d : devices) {
      const std::vector<std::string> missing = raybudget::core::missingRequirements(d);
      for (const std::string& m : missing) std::fprintf(stderr, "skipping a device: %s\n", m.c_str());
      if (missing.empty() && !physicalDevice) physicalDevice = d;
    }
    if (!physicalDevice) throw raybudget::Error("no Vulkan device can host raybudget");
    // raybudget's features and extensions; an engine would chain its own after them.
    setup = raybudget::core::deviceSetup(physicalDevice);
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, setup.queueFamily, 1, &priority};
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, setup.chain(), 0, 1, &qci};
    dci.enabledExtensionCount = uint32_t(setup.extensions.size());
    dci.ppEnabledExtensionNames = setup.extensions.data();
    check(vkCreateDevice(physicalDevice, &dci, nullptr, &device), "vkCreateDevice");
    vkGetDeviceQueue(device, setup.queueFamily, 0, &queue);
  }

  // Destroys what was made on the device (its messages are still collected).
  void release() {
    if (device) vkDeviceWaitIdle(device);
    for (auto c = cleanup.rbegin(); c != cleanup.rend(); ++c) (*c)();
    cleanup.clear();
  }

  ~Host() {
    release();
    if (device) vkDestroyDevice(device, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
  }

  raybudget::core::HostDevice lend() const {
    return {instance, physicalDevice, device, setup.queueFamily, queue, vkGetDeviceProcAddr, setup.rayQueryEnabled, setup.shaderFloat64Enabled};
  }

  VkDeviceMemory allocate(VkMemoryRequirements req, VkMemoryPropertyFlags flags) {
    VkPhysicalDeviceMemoryProperties p;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &p);
    uint32_t type = 0;
    while (type < p.memoryTypeCount && !((req.memoryTypeBits & (1u << type)) && (p.memoryTypes[type].propertyFlags & flags) == flags)) ++type;
    if (type == p.memoryTypeCount) throw raybudget::Error("no suitable memory type");
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(device, &ai, nullptr, &memory), "vkAllocateMemory");
    cleanup.push_back([this, memory] { vkFreeMemory(device, memory, nullptr); });
    return memory;
  }

  // A buffer in host-visible memory (an example's simplification), mapped.
  std::pair<VkBuffer, void*> buffer(VkDeviceSize size, VkBufferUsageFlags usage, const void* data = nullptr) {
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, size, usage};
    VkBuffer buffer = VK_NULL_HANDLE;
    check(vkCreateBuffer(device, &ci, nullptr, &buffer), "vkCreateBuffer");
    cleanup.push_back([this, buffer] { vkDestroyBuffer(device, buffer, nullptr); });
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, buffer, &req);
    const VkDeviceMemory memory = allocate(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
    void* mapped = nullptr;
    check(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    if (data) std::memcpy(mapped, data, size);
    return {buffer, mapped};
  }

  // One G-buffer plane: a device-local image with its view.
  std::pair<VkImage, VkImageView> image(VkFormat format, uint32_t w, uint32_t h) {
    const bool depth = format == VK_FORMAT_D32_SFLOAT;
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, nullptr, 0, VK_IMAGE_TYPE_2D, format, {w, h, 1}, 1, 1, VK_SAMPLE_COUNT_1_BIT};
    ci.usage = VK_IMAGE_USAGE_SAMPLED_BIT | (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    VkImage image = VK_NULL_HANDLE;
    check(vkCreateImage(device, &ci, nullptr, &image), "vkCreateImage");
    cleanup.push_back([this, image] { vkDestroyImage(device, image, nullptr); });
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    check(vkBindImageMemory(device, image, allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), 0), "vkBindImageMemory");
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, nullptr, 0, image, VK_IMAGE_VIEW_TYPE_2D, format};
    vi.subresourceRange = {VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    check(vkCreateImageView(device, &vi, nullptr, &view), "vkCreateImageView");
    cleanup.push_back([this, view] { vkDestroyImageView(device, view, nullptr); });
    return {image, view};
  }
};

void barrier(VkCommandBuffer cmd, VkImage image, bool depth, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
             VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, nullptr, srcStage, srcAccess, dstStage, dstAccess, from, to,
                          VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, image};
  b.subresourceRange = {VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1, 0, 1};
  VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  d.imageMemoryBarrierCount = 1;
  d.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &d);
}

// What the G-buffer shaders take per draw (gbuffer.vert's push block), and a draw.
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
    VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, code[i].second, code[i].first};
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
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.cullMode = VK_CULL_MODE_NONE;  // two-sided materials; glTF fronts are counter-clockwise
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  const VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO, nullptr, 0, VK_TRUE, VK_TRUE,
                                                    VK_COMPARE_OP_LESS};
  VkPipelineColorBlendAttachmentState blends[7] = {};
  for (auto& b : blends) b.colorWriteMask = 0xF;
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = 7;
  blend.pAttachments = blends;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO, nullptr, 0, 7, formats, VK_FORMAT_D32_SFLOAT};
  const VkGraphicsPipelineCreateInfo pci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering, 0, 2, stages, &input, &assembly, nullptr,
                                         &viewportState, &raster, &multisample, &depth, &blend, nullptr, layout};
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(vkCreateGraphicsPipelines(host.device, VK_NULL_HANDLE, 1, &pci, nullptr, &pipeline), "vkCreateGraphicsPipelines");
  for (VkShaderModule m : modules) vkDestroyShaderModule(host.device, m, nullptr);
  host.cleanup.push_back([&host, pipeline] { vkDestroyPipeline(host.device, pipeline, nullptr); });
  return pipeline;
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
      const glm::mat4 viewProj = rendered.projection(aspect) * rendered.view();

      // The host's geometry: each object's vertices in render space, one draw per primitive.
      std::vector<WorldVertex> vertices;
      std::vector<uint32_t> indices;
      std::vector<Draw> draws;
      for (const raybudget::Object& o : scene.objects) {
        const raybudget::Mesh& mesh = scene.meshes[o.mesh];
        const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(o.transform));
        const glm::mat4 model = raybudget::inRenderSpace(o.transform, origin);
        const uint32_t base = uint32_t(vertices.size());
        for (const raybudget::Vertex& v : mesh.vertices)
          vertices.push_back({glm::vec3(model * glm::vec4(v.position, 1.0f)), normalMatrix * v.normal, v.color});
        for (const raybudget::Primitive& p : mesh.primitives) {
          const raybudget::Material m = p.material >= 0 ? scene.materials[size_t(p.material)] : raybudget::Material{};
          draws.push_back({uint32_t(indices.size()), p.indexCount,
                           {viewProj, m.baseColorFactor, {m.metallic, m.roughness, m.transmission, m.ior}, {m.emissive, m.unlit ? 1.0f : 0.0f},
                            {o.id, uint32_t(std::max(p.material, 0)), m.doubleSided ? 1u : 0u, 0u}, glm::vec4(rendered.position, 1.0f)}});
          for (uint32_t i = 0; i < p.indexCount; ++i) indices.push_back(base + mesh.indices[p.firstIndex + i]);
        }
      }
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
      VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, host.setup.queueFamily};
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
        attachments[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, nullptr, colors[i].second, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        attachments[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        attachments[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        if (formats[i] == VK_FORMAT_R32_UINT) attachments[i].clearValue.color.uint32[0] = 0xFFFFFFFFu;  // no object
      }
      const VkPipelineStageFlags2 depthStages = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
      barrier(cmd, depthImage, true, VK_PIPELINE_STAGE_2_NONE, 0, depthStages,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
              VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
      VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, nullptr, depthView, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL};
      depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
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
      VkBufferImageCopy copy{};
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.imageExtent = {w, h, 1};
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
    for (const std::string& m : messages) std::fprintf(stderr, "validation: %s\n", m.c_str());
    if (!messages.empty()) return 1;
    std::printf("wrote minimal_host.png (%s)\n", validation ? "validation clean" : "validation off");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "minimal_host: %s\n", e.what());
    return 1;
  }
}
