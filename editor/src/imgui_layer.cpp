#include "imgui_layer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

namespace raybudget::editor {
namespace {

void checkImGuiVk(VkResult r) {
  if (r != VK_SUCCESS) std::fprintf(stderr, "editor: Dear ImGui's Vulkan backend: VkResult %d\n", int(r));
}

}  // namespace

ImGuiLayer::ImGuiLayer(const WindowDevice& wd, const Presenter& presenter) : wd_(wd) {
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pi.maxSets = 4;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  pool_ = make(wd.device(), vkCreateDescriptorPool, vkDestroyDescriptorPool, pi, "vkCreateDescriptorPool");

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout is fixed; nothing to remember
  ImGui::StyleColorsDark();
  // The canvas is cleared to the panels' colour, so their window draws no background: on a
  // software rasteriser that blended rectangle is most of the UI pass's time.
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 0.0f;
  ImGui_ImplGlfw_InitForVulkan(wd.window(), true);
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = wd.instance();
  info.PhysicalDevice = wd.physicalDevice();
  info.Device = wd.device();
  info.QueueFamily = wd.queueFamily();
  info.Queue = wd.queue();
  info.DescriptorPool = pool_;
  info.MinImageCount = presenter.minImageCount();
  info.ImageCount = std::max(presenter.imageCount(), presenter.minImageCount());
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkImGuiVk;
  ImGui_ImplVulkan_Init(&info, presenter.uiRenderPass());

  // The font atlas, uploaded once.
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = wd.commandPool();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(wd.device(), &ai, &cmd), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  ImGui_ImplVulkan_CreateFontsTexture(cmd);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  check(vkQueueSubmit(wd.queue(), 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
  check(vkQueueWaitIdle(wd.queue()), "vkQueueWaitIdle");
  vkFreeCommandBuffers(wd.device(), wd.commandPool(), 1, &cmd);
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImGuiLayer::~ImGuiLayer() {
  vkDeviceWaitIdle(wd_.device());
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiLayer::newFrame() {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

VkRect2D ImGuiLayer::render(VkExtent2D extent) {
  ImGui::Render();
  const ImDrawData* data = ImGui::GetDrawData();
  float x0 = float(extent.width), y0 = float(extent.height), x1 = 0.0f, y1 = 0.0f;
  for (int l = 0; l < data->CmdListsCount; ++l)
    for (const ImDrawCmd& c : data->CmdLists[l]->CmdBuffer) {
      x0 = std::min(x0, c.ClipRect.x);
      y0 = std::min(y0, c.ClipRect.y);
      x1 = std::max(x1, c.ClipRect.z);
      y1 = std::max(y1, c.ClipRect.w);
    }
  const int32_t left = std::clamp(int32_t(std::floor(x0)), 0, int32_t(extent.width));
  const int32_t top = std::clamp(int32_t(std::floor(y0)), 0, int32_t(extent.height));
  const int32_t right = std::clamp(int32_t(std::ceil(x1)), left, int32_t(extent.width));
  const int32_t bottom = std::clamp(int32_t(std::ceil(y1)), top, int32_t(extent.height));
  return {{left, top}, {uint32_t(right - left), uint32_t(bottom - top)}};
}

void ImGuiLayer::record(VkCommandBuffer cmd) { ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd); }

}  // namespace raybudget::editor
