#include "imgui_layer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>

namespace raybudget::editor {

ImGuiLayer::ImGuiLayer(const WindowDevice& wd, const Presenter& presenter) : wd_(wd) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout is fixed; nothing to remember
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  // The canvas is cleared to the panels' colour, so their window draws no background: on a
  // software rasteriser that blended rectangle is most of the UI pass's time.
  style.Colors[ImGuiCol_WindowBg].w = 0.0f;
  // Square corners and no anti-aliased fringes: on lavapipe the UI pass costs per
  // primitive, and the fringes' thin triangles took 0.3-0.4 ms of it. At the UI's 1:1 pixel
  // scale only the plot's polyline and the headers' arrows look different.
  style.AntiAliasedLines = false;
  style.AntiAliasedFill = false;
  style.ScrollbarRounding = 0.0f;
  // And per blended pixel: widgets are outlined rather than filled, and table headers and
  // scrollbars have no background (with an object picked, 2.35 to 1.84 ms at 1280x720; the
  // filled sliders, input fields and the plot's frame alone were 0.35 ms).
  style.Colors[ImGuiCol_FrameBg].w = 0.0f;
  style.FrameBorderSize = 1.0f;
  style.Colors[ImGuiCol_TableHeaderBg].w = 0.0f;
  style.Colors[ImGuiCol_ScrollbarBg].w = 0.0f;
  ImGui_ImplGlfw_InitForVulkan(wd.window(), true);
  renderer_ = std::make_unique<UiRenderer>(wd, presenter.uiRenderPass());
}

ImGuiLayer::~ImGuiLayer() {
  vkDeviceWaitIdle(wd_.device());
  renderer_.reset();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiLayer::newFrame() {
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

void ImGuiLayer::record(VkCommandBuffer cmd) { renderer_->record(cmd, *ImGui::GetDrawData()); }

}  // namespace raybudget::editor
