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

// The host's own instance, messenger and device: what an engine has before raybudget.
struct HostVulkan {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  raybudget::core::DeviceSetup setup;

  explicit HostVulkan(bool validation) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "minimal_host";
    app.apiVersion = VK_API_VERSION_1_3;
    VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    dbg.pfnUserCallback = onMessage;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    if (validation) {
      ici.pNext = &dbg;
      ici.enabledLayerCount = 1;
      ici.ppEnabledLayerNames = &layer;
      ici.enabledExtensionCount = 1;
      ici.ppEnabledExtensionNames = &extension;
    }
    check(vkCreateInstance(&ici, nullptr, &instance), "vkCreateInstance");
    if (validation) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
      check(create(instance, &dbg, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
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
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = setup.queueFamily;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.pNext = setup.chain();
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = uint32_t(setup.extensions.size());
    dci.ppEnabledExtensionNames = setup.extensions.data();
    check(vkCreateDevice(physicalDevice, &dci, nullptr, &device), "vkCreateDevice");
    vkGetDeviceQueue(device, setup.queueFamily, 0, &queue);
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.queueFamilyIndex = setup.queueFamily;
    check(vkCreateCommandPool(device, &pci, nullptr, &pool), "vkCreateCommandPool");
  }

  ~HostVulkan() {
    if (pool) vkDestroyCommandPool(device, pool, nullptr);
    if (device) vkDestroyDevice(device, nullptr);
    if (messenger) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      destroy(instance, messenger, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
  }

  raybudget::core::HostDevice lend() const {
    return {instance, physicalDevice, device, setup.queueFamily, queue, vkGetDeviceProcAddr, setup.rayQueryEnabled, setup.shaderFloat64Enabled};
  }

  uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties p;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &p);
    for (uint32_t i = 0; i < p.memoryTypeCount; ++i)
      if ((bits & (1u << i)) && (p.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw raybudget::Error("no suitable memory type");
  }
};

// A buffer in host-visible memory (an example's simplification), mapped.
struct HostBuffer {
  const HostVulkan& vk;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  HostBuffer(const HostVulkan& v, VkDeviceSize size, VkBufferUsageFlags usage, const void* data = nullptr) : vk(v) {
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = size;
    ci.usage = usage;
    check(vkCreateBuffer(vk.device, &ci, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(vk.device, buffer, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = vk.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check(vkAllocateMemory(vk.device, &ai, nullptr, &memory), "vkAllocateMemory");
    check(vkBindBufferMemory(vk.device, buffer, memory, 0), "vkBindBufferMemory");
    check(vkMapMemory(vk.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    if (data) std::memcpy(mapped, data, size);
  }
  ~HostBuffer() {
    vkDestroyBuffer(vk.device, buffer, nullptr);
    vkFreeMemory(vk.device, memory, nullptr);
  }
};

// One G-buffer plane: a device-local image with its view.
struct HostImage {
  const HostVulkan& vk;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format;
  VkImageAspectFlags aspect;
  HostImage(const HostVulkan& v, VkFormat f, uint32_t w, uint32_t h)
      : vk(v), format(f), aspect(f == VK_FORMAT_D32_SFLOAT ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT) {
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = f;
    ci.extent = {w, h, 1};
    ci.mipLevels = ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.usage = VK_IMAGE_USAGE_SAMPLED_BIT |
               (aspect == VK_IMAGE_ASPECT_DEPTH_BIT ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    check(vkCreateImage(vk.device, &ci, nullptr, &image), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(vk.device, image, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = vk.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check(vkAllocateMemory(vk.device, &ai, nullptr, &memory), "vkAllocateMemory");
    check(vkBindImageMemory(vk.device, image, memory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = f;
    vi.subresourceRange = {aspect, 0, 1, 0, 1};
    check(vkCreateImageView(vk.device, &vi, nullptr, &view), "vkCreateImageView");
  }
  ~HostImage() {
    vkDestroyImageView(vk.device, view, nullptr);
    vkDestroyImage(vk.device, image, nullptr);
    vkFreeMemory(vk.device, memory, nullptr);
  }
};

void barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
             VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, 1, 0, 1};
  VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  d.imageMemoryBarrierCount = 1;
  d.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &d);
}

// What the G-buffer shaders take per draw (gbuffer.vert's push block).
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

VkShaderModule shaderModule(VkDevice device, const uint32_t* code, size_t bytes) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = bytes;
  ci.pCode = code;
  VkShaderModule m = VK_NULL_HANDLE;
  check(vkCreateShaderModule(device, &ci, nullptr, &m), "vkCreateShaderModule");
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: minimal_host SCENE.gltf [--validation]\n");
    return 2;
  }
  const bool validation = argc > 2 && std::strcmp(argv[2], "--validation") == 0;
  try {
    HostVulkan host(validation);
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
      const glm::mat4 viewProj = camera.projection(aspect) * camera.view();

      // The host's geometry: each object's vertices in world space, one draw per primitive.
      struct WorldVertex {
        glm::vec3 position, normal;
        glm::vec4 color;
      };
      std::vector<WorldVertex> vertices;
      std::vector<uint32_t> indices;
      std::vector<Draw> draws;
      for (const raybudget::Object& o : scene.objects) {
        const raybudget::Mesh& mesh = scene.meshes[o.mesh];
        const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(o.transform));
        const uint32_t base = uint32_t(vertices.size());
        for (const raybudget::Vertex& v : mesh.vertices)
          vertices.push_back({glm::vec3(o.transform * glm::vec4(v.position, 1.0f)), normalMatrix * v.normal, v.color});
        for (const raybudget::Primitive& p : mesh.primitives) {
          const raybudget::Material m = p.material >= 0 ? scene.materials[size_t(p.material)] : raybudget::Material{};
          Draw d{uint32_t(indices.size()), p.indexCount, {}};
          d.push = {viewProj, m.baseColorFactor, {m.metallic, m.roughness, m.transmission, m.ior}, {m.emissive, m.unlit ? 1.0f : 0.0f},
                    {o.id, uint32_t(std::max(p.material, 0)), m.doubleSided ? 1u : 0u, 0u}, glm::vec4(camera.position, 1.0f)};
          for (uint32_t i = 0; i < p.indexCount; ++i) indices.push_back(base + mesh.indices[p.firstIndex + i]);
          draws.push_back(d);
        }
      }
      const HostBuffer vertexBuffer(host, vertices.size() * sizeof(WorldVertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, vertices.data());
      const HostBuffer indexBuffer(host, indices.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, indices.data());

      // The G-buffer in raybudget's encoding (core::GBuffer), and the pipeline that fills it.
      HostImage depth(host, VK_FORMAT_D32_SFLOAT, w, h), normal(host, VK_FORMAT_R16G16B16A16_SFLOAT, w, h),
          baseMetal(host, VK_FORMAT_R8G8B8A8_UNORM, w, h), roughTransIor(host, VK_FORMAT_R16G16B16A16_SFLOAT, w, h),
          emissive(host, VK_FORMAT_R16G16B16A16_SFLOAT, w, h), objectId(host, VK_FORMAT_R32_UINT, w, h), materialId(host, VK_FORMAT_R32_UINT, w, h),
          position(host, VK_FORMAT_R32G32B32A32_SFLOAT, w, h);
      const HostImage* colors[] = {&normal, &baseMetal, &roughTransIor, &emissive, &objectId, &materialId, &position};
      VkFormat colorFormats[7];
      for (int i = 0; i < 7; ++i) colorFormats[i] = colors[i]->format;

      const VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawPush)};
      VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
      lci.pushConstantRangeCount = 1;
      lci.pPushConstantRanges = &range;
      VkPipelineLayout layout = VK_NULL_HANDLE;
      check(vkCreatePipelineLayout(host.device, &lci, nullptr, &layout), "vkCreatePipelineLayout");
      const VkShaderModule vert = shaderModule(host.device, kSpirv_gbuffer_vert, sizeof(kSpirv_gbuffer_vert));
      const VkShaderModule frag = shaderModule(host.device, kSpirv_gbuffer_frag, sizeof(kSpirv_gbuffer_frag));
      VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}, {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
      stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
      stages[0].module = vert;
      stages[0].pName = "main";
      stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
      stages[1].module = frag;
      stages[1].pName = "main";
      const VkVertexInputBindingDescription binding{0, sizeof(WorldVertex), VK_VERTEX_INPUT_RATE_VERTEX};
      const VkVertexInputAttributeDescription attributes[] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(WorldVertex, position)},
                                                              {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(WorldVertex, normal)},
                                                              {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(WorldVertex, color)}};
      VkPipelineVertexInputStateCreateInfo input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
      input.vertexBindingDescriptionCount = 1;
      input.pVertexBindingDescriptions = &binding;
      input.vertexAttributeDescriptionCount = 3;
      input.pVertexAttributeDescriptions = attributes;
      VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
      assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
      const VkViewport viewport{0.0f, 0.0f, float(w), float(h), 0.0f, 1.0f};
      const VkRect2D scissor{{0, 0}, {w, h}};
      VkPipelineViewportStateCreateInfo viewportState{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
      viewportState.viewportCount = viewportState.scissorCount = 1;
      viewportState.pViewports = &viewport;
      viewportState.pScissors = &scissor;
      VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
      raster.cullMode = VK_CULL_MODE_NONE;  // two-sided materials; glTF fronts are counter-clockwise
      raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
      raster.lineWidth = 1.0f;
      VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
      multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
      VkPipelineDepthStencilStateCreateInfo depthState{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
      depthState.depthTestEnable = depthState.depthWriteEnable = VK_TRUE;
      depthState.depthCompareOp = VK_COMPARE_OP_LESS;
      VkPipelineColorBlendAttachmentState blends[7] = {};
      for (auto& b : blends) b.colorWriteMask = 0xF;
      VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
      blend.attachmentCount = 7;
      blend.pAttachments = blends;
      VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
      rendering.colorAttachmentCount = 7;
      rendering.pColorAttachmentFormats = colorFormats;
      rendering.depthAttachmentFormat = VK_FORMAT_D32_SFLOAT;
      VkGraphicsPipelineCreateInfo pci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
      pci.pNext = &rendering;
      pci.stageCount = 2;
      pci.pStages = stages;
      pci.pVertexInputState = &input;
      pci.pInputAssemblyState = &assembly;
      pci.pViewportState = &viewportState;
      pci.pRasterizationState = &raster;
      pci.pMultisampleState = &multisample;
      pci.pDepthStencilState = &depthState;
      pci.pColorBlendState = &blend;
      pci.layout = layout;
      VkPipeline pipeline = VK_NULL_HANDLE;
      check(vkCreateGraphicsPipelines(host.device, VK_NULL_HANDLE, 1, &pci, nullptr, &pipeline), "vkCreateGraphicsPipelines");

      // One frame: the host's raster, raybudget's frame, the composed image copied out.
      const HostBuffer readback(host, VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
      VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
      cai.commandPool = host.pool;
      cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
      cai.commandBufferCount = 1;
      VkCommandBuffer cmd = VK_NULL_HANDLE;
      check(vkAllocateCommandBuffers(host.device, &cai, &cmd), "vkAllocateCommandBuffers");
      VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
      bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
      check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
      VkRenderingAttachmentInfo attachments[7];
      for (int i = 0; i < 7; ++i) {
        barrier(cmd, colors[i]->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        attachments[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        attachments[i].imageView = colors[i]->view;
        attachments[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        attachments[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        attachments[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        if (colors[i]->format == VK_FORMAT_R32_UINT) attachments[i].clearValue.color.uint32[0] = 0xFFFFFFFFu;  // no object
      }
      barrier(cmd, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_PIPELINE_STAGE_2_NONE, 0,
              VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
              VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
      VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
      depthAttachment.imageView = depth.view;
      depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
      depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      depthAttachment.clearValue.depthStencil = {1.0f, 0};
      VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
      ri.renderArea = scissor;
      ri.layerCount = 1;
      ri.colorAttachmentCount = 7;
      ri.pColorAttachments = attachments;
      ri.pDepthAttachment = &depthAttachment;
      vkCmdBeginRendering(cmd, &ri);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
      const VkDeviceSize offset = 0;
      vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer.buffer, &offset);
      vkCmdBindIndexBuffer(cmd, indexBuffer.buffer, 0, VK_INDEX_TYPE_UINT32);
      for (const Draw& d : draws) {
        vkCmdPushConstants(cmd, layout, range.stageFlags, 0, sizeof(DrawPush), &d.push);
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, 0, 0);
      }
      vkCmdEndRendering(cmd);
      // raybudget reads the G-buffer in compute shaders, SHADER_READ_ONLY_OPTIMAL.
      for (const HostImage* c : colors)
        barrier(cmd, c->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
      barrier(cmd, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
              VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);

      const raybudget::core::GBuffer gbuffer{depth.view,    normal.view,     baseMetal.view, roughTransIor.view, emissive.view,
                                             objectId.view, materialId.view, position.view,  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      core.recordFrame(cmd, camera, &gbuffer);

      // The composed image (tonemapped sRGB, GENERAL) out to the host.
      const raybudget::core::FrameOutputs out = core.outputs();
      VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
      mb.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
      mb.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
      mb.dstStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
      mb.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
      VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
      dep.memoryBarrierCount = 1;
      dep.pMemoryBarriers = &mb;
      vkCmdPipelineBarrier2(cmd, &dep);
      VkBufferImageCopy copy{};
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.imageExtent = {w, h, 1};
      vkCmdCopyImageToBuffer(cmd, out.ldr, out.layout, readback.buffer, 1, &copy);
      mb.srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
      mb.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
      mb.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
      mb.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
      vkCmdPipelineBarrier2(cmd, &dep);
      check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

      VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
      VkFence fence = VK_NULL_HANDLE;
      check(vkCreateFence(host.device, &fci, nullptr, &fence), "vkCreateFence");
      VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
      si.commandBufferCount = 1;
      si.pCommandBuffers = &cmd;
      check(vkQueueSubmit(host.queue, 1, &si, fence), "vkQueueSubmit");
      check(vkWaitForFences(host.device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
      const auto* pixels = static_cast<const uint8_t*>(readback.mapped);
      raybudget::writePng("minimal_host.png", w, h, std::vector<uint8_t>(pixels, pixels + size_t(w) * h * 4));

      vkDestroyFence(host.device, fence, nullptr);
      vkDestroyPipeline(host.device, pipeline, nullptr);
      vkDestroyShaderModule(host.device, vert, nullptr);
      vkDestroyShaderModule(host.device, frag, nullptr);
      vkDestroyPipelineLayout(host.device, layout, nullptr);
    }
    vkDeviceWaitIdle(host.device);
    for (const std::string& m : messages) std::fprintf(stderr, "validation: %s\n", m.c_str());
    if (!messages.empty()) return 1;
    std::printf("wrote minimal_host.png (%s)\n", validation ? "validation clean" : "validation off");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "minimal_host: %s\n", e.what());
    return 1;
  }
}
