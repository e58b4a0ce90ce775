// Dear ImGui on the editor's window and device (Debian's libimgui-dev 1.86: its GLFW backend
// for input, our UiRenderer for drawing): set up once, a new frame per editor frame, its
// draw data recorded into the canvas's UI render pass.
#pragma once
#include <memory>

#include "presenter.h"
#include "ui_renderer.h"
#include "window_device.h"

namespace raybudget::editor {

// The panels' background: the colour the canvas is cleared to.
inline constexpr float kPanelBackground[4] = {0.06f, 0.06f, 0.06f, 1.0f};

class ImGuiLayer {
 public:
  ImGuiLayer(const WindowDevice& wd, const Presenter& presenter);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  void newFrame();
  // Ends the UI frame (ImGui::Render); returns the canvas area its draws touch (the union
  // of their clip rectangles, within `extent`), the render area of the UI pass.
  VkRect2D render(VkExtent2D extent);
  // Records the draw data; inside the UI render pass.
  void record(VkCommandBuffer cmd);

 private:
  const WindowDevice& wd_;
  std::unique_ptr<UiRenderer> renderer_;
};

}  // namespace raybudget::editor
