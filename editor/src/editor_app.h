// The editor's frame loop: input (camera, picking), the script's next command, the panels,
// then one frame recorded into one command buffer: the core's frame, the viewport overlay,
// the canvas (viewport copied in, the UI drawn over), the blit to the swapchain, and
// optionally the canvas copied out for a screenshot. One frame in flight: the editor waits
// for each before reading the objects' metrics, the pick and the screenshot.
#pragma once
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "imgui_layer.h"
#include "options.h"
#include "overlay_pass.h"
#include "panels.h"
#include "presenter.h"
#include "script.h"
#include "session.h"
#include "window_device.h"

namespace raybudget::editor {

class EditorApp {
 public:
  explicit EditorApp(const EditorOptions& options);
  ~EditorApp();
  // Runs until the window closes, the script quits or --frames is reached; the exit status:
  // 0, 2 when a script expectation failed, 3 on validation messages.
  int run();

 private:
  bool frame();  // false: quit
  void handleInput();
  void runScript();
  void execute(const ScriptCommand& c);
  void apply(const UiRequests& r);
  void pick(int objectId);
  void record(VkCommandBuffer cmd, uint32_t imageIndex);
  void afterFrame();
  void writeScreenshot(const std::string& path);
  void printStats() const;
  glm::ivec2 renderPixel(double windowX, double windowY) const;
  bool inViewport(double windowX, double windowY) const;

  EditorOptions options_;
  Scene loaded_;
  std::unique_ptr<WindowDevice> wd_;
  std::unique_ptr<Presenter> presenter_;
  std::unique_ptr<ImGuiLayer> imgui_;
  std::unique_ptr<Session> session_;
  std::unique_ptr<OverlayPass> overlay_;
  Panels panels_;
  UiView view_;
  Camera camera_, startCamera_;

  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  Owned<VkFence> fence_;
  Owned<VkSemaphore> acquired_;
  Owned<VkQueryPool> uiQueries_;
  HostBuffer screenshotBuffer_;

  std::vector<ScriptCommand> script_;
  size_t scriptNext_ = 0;
  uint64_t waitFrames_ = 0;
  bool quit_ = false;
  int exitStatus_ = 0;
  std::optional<glm::ivec2> pendingPick_;
  std::optional<std::string> pendingScreenshot_;
  bool leftDragged_ = false;
  uint64_t frames_ = 0;
  std::vector<double> uiGpuMs_, emptyBracketMs_, uiCpuMs_, frameMs_;
  std::chrono::steady_clock::time_point lastFrame_;
};

}  // namespace raybudget::editor
