#include "editor_app.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "camera_control.h"
#include "raybudget/error.h"
#include "raybudget/image_io.h"

namespace raybudget::editor {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

constexpr float kDegrees = 0.01745329252f;

}  // namespace

EditorApp::EditorApp(const EditorOptions& options) : options_(options) {
  loaded_ = loadScene(options.scene);
  for (const std::string& w : loaded_.warnings) std::printf("editor: %s: %s\n", options.scene.c_str(), w.c_str());
  if (!options.script.empty()) script_ = loadScript(options.script);
  wd_ = std::make_unique<WindowDevice>("raybudget-editor: " + loaded_.path.filename().string(), options.windowWidth, options.windowHeight,
                                       options.settings.validation, options.settings.device);
  presenter_ = std::make_unique<Presenter>(*wd_);
  imgui_ = std::make_unique<ImGuiLayer>(*wd_, *presenter_);
  session_ = std::make_unique<Session>(wd_->lend(), loaded_, options.settings);
  session_->beforeCoreRebuild = [this] { overlay_.reset(); };  // the overlay holds views of its images
  const RenderSettings& s = session_->settings();
  overlay_ = std::make_unique<OverlayPass>(*wd_, session_->core(), VkExtent2D{s.width, s.height}, uint32_t(loaded_.objects.size()));
  view_.overlay = parseOverlay(options.overlay);
  startCamera_ = camera_ = defaultCamera(loaded_, float(s.width) / float(s.height));

  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = wd_->commandPool();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(wd_->device(), &ai, &cmd_), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fence_ = make(wd_->device(), vkCreateFence, vkDestroyFence, fi, "vkCreateFence");
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  acquired_ = make(wd_->device(), vkCreateSemaphore, vkDestroySemaphore, si, "vkCreateSemaphore");
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = 4;
  uiQueries_ = make(wd_->device(), vkCreateQueryPool, vkDestroyQueryPool, qi, "vkCreateQueryPool");
  std::printf("editor: %s on %s, viewport %ux%u, policy %s, T %.1f ms\n", loaded_.path.string().c_str(), wd_->deviceName().c_str(), s.width,
              s.height, policyName(s.policy), s.budgetMs);
}

EditorApp::~EditorApp() {
  if (wd_) vkDeviceWaitIdle(wd_->device());
  overlay_.reset();
  session_.reset();
  imgui_.reset();
  if (cmd_) vkFreeCommandBuffers(wd_->device(), wd_->commandPool(), 1, &cmd_);
  fence_.reset();
  acquired_.reset();
  uiQueries_.reset();
  screenshotBuffer_ = {};
  presenter_.reset();
}

int EditorApp::run() {
  lastFrame_ = std::chrono::steady_clock::now();
  while (frame()) {
  }
  printStats();
  if (!wd_->validationMessages().empty()) {
    std::printf("editor: %zu validation messages\n", wd_->validationMessages().size());
    return 3;
  }
  return exitStatus_;
}

bool EditorApp::frame() {
  glfwPollEvents();
  if (glfwWindowShouldClose(wd_->window())) {
    glfwSetWindowShouldClose(wd_->window(), GLFW_FALSE);
    if (!session_->modified()) return false;
    view_.quitPrompt = true;
  }
  uint32_t imageIndex = 0;
  if (!presenter_->acquire(acquired_, imageIndex)) return !quit_;
  const auto uiStart = std::chrono::steady_clock::now();
  imgui_->newFrame();
  handleInput();
  if (!script_.empty()) runScript();
  if (!options_.screenshot.empty() && script_.empty() && frames_ + 1 == (options_.frames ? options_.frames : 3)) {
    pendingScreenshot_ = options_.screenshot;
    quit_ = true;
  }
  view_.panelWidth = float(options_.panelWidth);
  view_.panelX = float(presenter_->extent().width) - view_.panelWidth;
  view_.height = float(presenter_->extent().height);
  const UiRequests requests = panels_.draw(*session_, view_);
  uiCpuMs_.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - uiStart).count());
  apply(requests);
  overlay_->setTints(overlayTints(view_.overlay, session_->rows()));

  check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
  record(cmd_, imageIndex);
  check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
  const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  const VkSemaphore done = presenter_->renderDone(imageIndex);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = acquired_.ptr();
  submit.pWaitDstStageMask = &waitStage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd_;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &done;
  check(vkQueueSubmit(wd_->queue(), 1, &submit, fence_), "vkQueueSubmit");
  presenter_->present(imageIndex);
  afterFrame();
  ++frames_;
  if (options_.frames && frames_ >= options_.frames) quit_ = true;
  const std::string title = "raybudget-editor: " + loaded_.path.filename().string() + (session_->modified() ? " *" : "");
  glfwSetWindowTitle(wd_->window(), title.c_str());
  return !quit_;
}

void EditorApp::record(VkCommandBuffer cmd, uint32_t imageIndex) {
  vkCmdResetQueryPool(cmd, uiQueries_, 0, 4);
  session_->core().recordFrame(cmd, camera_);
  overlay_->record(cmd, pendingPick_.value_or(glm::ivec2(-1)), view_.picked >= 0 ? uint32_t(view_.picked) : OverlayPass::kNoObject,
                   view_.overlay == Overlay::Traced);

  // The canvas: the panels' background, the viewport on the left, the UI over both.
  const VkImage canvas = presenter_->canvas();
  const VkExtent2D extent = presenter_->extent();
  imageBarrier(cmd, canvas, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
               VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  const VkClearColorValue background{{kPanelBackground[0], kPanelBackground[1], kPanelBackground[2], kPanelBackground[3]}};
  const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, canvas, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &background, 1, &all);
  imageBarrier(cmd, canvas, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  const VkExtent2D render = overlay_->extent();
  VkImageBlit blit{};
  blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(render.width), int32_t(render.height), 1};
  blit.dstOffsets[1] = {std::max(1, int32_t(extent.width) - int32_t(options_.panelWidth)), int32_t(extent.height), 1};
  vkCmdBlitImage(cmd, overlay_->viewport(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, canvas, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                 VK_FILTER_LINEAR);

  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, uiQueries_, 0);
  VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rp.renderPass = presenter_->uiRenderPass();
  rp.framebuffer = presenter_->canvasFramebuffer();
  rp.renderArea = imgui_->render(extent);  // only where the UI draws: llvmpipe loads and stores the whole area
  vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  imgui_->record(cmd);
  vkCmdEndRenderPass(cmd);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, uiQueries_, 1);
  // An empty bracket: what the timestamps themselves cost, said beside the UI's time.
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, uiQueries_, 2);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, uiQueries_, 3);

  if (pendingScreenshot_) {
    const VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
    if (screenshotBuffer_.size != bytes) screenshotBuffer_ = createHostBuffer(*wd_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, canvas, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, screenshotBuffer_.buffer, 1, &copy);
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    mb.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    mb.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    mb.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &mb;
    vkCmdPipelineBarrier2(cmd, &dep);
  }
  presenter_->recordBlitToSwapchain(cmd, imageIndex);
}

void EditorApp::afterFrame() {
  check(vkWaitForFences(wd_->device(), 1, fence_.ptr(), VK_TRUE, UINT64_MAX), "vkWaitForFences");
  check(vkResetFences(wd_->device(), 1, fence_.ptr()), "vkResetFences");
  session_->collectFrame();
  if (pendingPick_) {
    const uint32_t id = overlay_->pickedId();
    pick(id == OverlayPass::kNoObject ? -1 : int(id));
    pendingPick_.reset();
  }
  uint64_t stamps[4] = {0, 0, 0, 0};
  if (vkGetQueryPoolResults(wd_->device(), uiQueries_, 0, 4, sizeof(stamps), stamps, sizeof(uint64_t), VK_QUERY_RESULT_64_BIT) == VK_SUCCESS) {
    view_.uiGpuMs = double(stamps[1] - stamps[0]) * wd_->timestampPeriodNs() * 1e-6;
    uiGpuMs_.push_back(view_.uiGpuMs);
    emptyBracketMs_.push_back(double(stamps[3] - stamps[2]) * wd_->timestampPeriodNs() * 1e-6);
  }
  view_.uiCpuMs = uiCpuMs_.empty() ? 0.0 : uiCpuMs_.back();
  const auto now = std::chrono::steady_clock::now();
  view_.frameMs = std::chrono::duration<double, std::milli>(now - lastFrame_).count();
  frameMs_.push_back(view_.frameMs);
  lastFrame_ = now;
  if (pendingScreenshot_) {
    writeScreenshot(*pendingScreenshot_);
    pendingScreenshot_.reset();
  }
}

void EditorApp::writeScreenshot(const std::string& path) {
  const VkExtent2D extent = presenter_->extent();
  const auto* bytes = static_cast<const uint8_t*>(screenshotBuffer_.mapped);
  writePng(path, extent.width, extent.height, std::vector<uint8_t>(bytes, bytes + screenshotBuffer_.size));
  std::printf("editor: wrote %s (%ux%u)\n", path.c_str(), extent.width, extent.height);
}

bool EditorApp::inViewport(double x, double y) const {
  const VkExtent2D extent = presenter_->extent();
  return x >= 0 && y >= 0 && x < double(extent.width) - options_.panelWidth && y < double(extent.height);
}

glm::ivec2 EditorApp::renderPixel(double x, double y) const {
  const VkExtent2D extent = presenter_->extent(), render = overlay_->extent();
  const double w = std::max(1.0, double(extent.width) - options_.panelWidth);
  return {int(x * render.width / w), int(y * render.height / double(extent.height))};
}

void EditorApp::handleInput() {
  ImGuiIO& io = ImGui::GetIO();
  GLFWwindow* window = wd_->window();
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  if (!io.WantCaptureMouse && inViewport(x, y)) {
    const float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
    if (io.MouseDown[0] && (dx != 0.0f || dy != 0.0f)) camera_ = orbit(camera_, -dx * 0.005f, dy * 0.005f);
    if (ImGui::IsMouseReleased(0) && io.MouseDragMaxDistanceSqr[0] < 9.0f) pendingPick_ = renderPixel(x, y);
    if (io.MouseDown[1] && (dx != 0.0f || dy != 0.0f)) camera_ = look(camera_, -dx * 0.003f, -dy * 0.003f);
    if (io.MouseWheel != 0.0f) camera_ = dolly(camera_, io.MouseWheel * 0.1f);
  }
  if (!io.WantCaptureKeyboard) {
    const float step = glm::length(loaded_.boundsMax - loaded_.boundsMin) * 0.3f * io.DeltaTime;
    auto key = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS ? step : 0.0f; };
    const float forward = key(GLFW_KEY_W) - key(GLFW_KEY_S), right = key(GLFW_KEY_D) - key(GLFW_KEY_A), up = key(GLFW_KEY_E) - key(GLFW_KEY_Q);
    if (forward != 0.0f || right != 0.0f || up != 0.0f) camera_ = fly(camera_, forward, right, up);
    if (glfwGetKey(window, GLFW_KEY_HOME) == GLFW_PRESS) camera_ = startCamera_;
  }
}

void EditorApp::pick(int objectId) {
  view_.picked = objectId;
  view_.message = objectId >= 0 ? "picked " + loaded_.objects[size_t(objectId)].name : "picked nothing";
  std::printf("editor: %s\n", view_.message.c_str());
}

void EditorApp::apply(const UiRequests& r) {
  std::string message;
  auto say = [&] {
    view_.message = message;
    std::printf("editor: %s\n", message.c_str());
  };
  const uint32_t generation = session_->coreGeneration();
  if (r.pick) pick(*r.pick);
  if (r.set) {
    session_->setParam(view_.picked >= 0 ? uint32_t(view_.picked) : UINT32_MAX, r.set->first, r.set->second, message);
    say();
  }
  if (r.undo) {
    session_->undo(message);
    say();
  }
  if (r.redo) {
    session_->redo(message);
    say();
  }
  if (r.budget) {
    session_->setBudget(*r.budget, message);
    say();
  }
  if (r.policy) {
    session_->setPolicy(*r.policy, message);
    say();
  }
  if (r.tracer) {
    session_->setTracer(*r.tracer, message);
    say();
  }
  if (session_->coreGeneration() != generation) {  // a new tracer (or its undo): a new context
    const RenderSettings& s = session_->settings();
    overlay_ = std::make_unique<OverlayPass>(*wd_, session_->core(), VkExtent2D{s.width, s.height}, uint32_t(loaded_.objects.size()));
  }
  if (r.overlay) view_.overlay = *r.overlay;
  if (r.save) {
    const std::string path = r.saveAs.empty() ? loaded_.path.string() : r.saveAs;
    try {
      session_->save(path);
      message = "saved " + path;
    } catch (const Error& e) {
      message = e.what();
    }
    say();
  }
  if (r.resetCamera) camera_ = startCamera_;
  if (r.quit) quit_ = true;
}

void EditorApp::runScript() {
  if (waitFrames_ > 0) {
    --waitFrames_;
    return;
  }
  if (scriptNext_ >= script_.size()) {
    quit_ = true;
    if (!options_.screenshot.empty()) pendingScreenshot_ = options_.screenshot;
    return;
  }
  execute(script_[scriptNext_++]);
}

void EditorApp::execute(const ScriptCommand& c) {
  const std::string where = options_.script + ":" + std::to_string(c.line) + ": ";
  auto fail = [&](const std::string& what) {
    std::printf("editor: %s%s\n", where.c_str(), what.c_str());
    exitStatus_ = 2;
    quit_ = true;
  };
  UiRequests r;
  switch (c.kind) {
    case CommandKind::PickName: {
      const int id = session_->findObject(c.text);
      if (id < 0) return fail("no object is named '" + c.text + "'");
      r.pick = id;
      break;
    }
    case CommandKind::PickPixel:
      if (!inViewport(c.value, c.value2)) return fail("pick " + std::to_string(c.value) + " " + std::to_string(c.value2) + " is outside the viewport");
      pendingPick_ = renderPixel(c.value, c.value2);
      break;
    case CommandKind::Set: r.set = {parseParam(c.text), c.value}; break;
    case CommandKind::Budget: r.budget = c.value; break;
    case CommandKind::Policy:
      try {
        r.policy = parsePolicy(c.text);
      } catch (const Error& e) {
        return fail(e.what());
      }
      break;
    case CommandKind::Tracer:
      if (c.text != "compute" && c.text != "native") return fail("tracer must be compute or native, got '" + c.text + "'");
      r.tracer = c.text == "native" ? Tracer::Native : Tracer::Compute;
      break;
    case CommandKind::Overlay:
      try {
        r.overlay = parseOverlay(c.text);
      } catch (const Error& e) {
        return fail(e.what());
      }
      break;
    case CommandKind::CameraOrbit: camera_ = orbit(camera_, float(c.value) * kDegrees, 0.0f); break;
    case CommandKind::CameraFly: camera_ = fly(camera_, float(c.value), 0.0f, 0.0f); break;
    case CommandKind::CameraReset: r.resetCamera = true; break;
    case CommandKind::Wait: waitFrames_ = c.value > 0 ? uint64_t(c.value) - 1 : 0; break;
    case CommandKind::Screenshot: pendingScreenshot_ = c.text; break;
    case CommandKind::Save:
      r.save = true;
      r.saveAs = c.text;
      break;
    case CommandKind::Dump: {
      std::ofstream out(c.text);
      out << rowsCsv(session_->rows());
      if (!out) return fail("cannot write " + c.text);
      std::printf("editor: wrote %s\n", c.text.c_str());
      break;
    }
    case CommandKind::Undo: r.undo = true; break;
    case CommandKind::Redo: r.redo = true; break;
    case CommandKind::Quit:
      if (session_->modified()) std::printf("editor: quitting with unsaved changes (discarded)\n");
      quit_ = true;
      break;
    case CommandKind::Close: glfwSetWindowShouldClose(wd_->window(), GLFW_TRUE); break;
    case CommandKind::ExpectPrompt:
      if (!view_.quitPrompt) return fail("expected the unsaved-changes prompt, it is not open");
      std::printf("editor: as expected, the unsaved-changes prompt is open\n");
      break;
    case CommandKind::ExpectPicked: {
      const std::string picked = view_.picked >= 0 ? loaded_.objects[size_t(view_.picked)].name : "none";
      if (picked != c.text) return fail("expected " + c.text + " picked, " + picked + " is");
      std::printf("editor: as expected, %s is picked\n", picked.c_str());
      break;
    }
    case CommandKind::ExpectSelected: {
      const int id = session_->findObject(c.text);
      if (id < 0) return fail("no object is named '" + c.text + "'");
      const bool selected = session_->rows()[size_t(id)].metrics.selectedItems != 0;
      if (selected != (c.value2 != 0.0)) return fail("expected " + c.text + (c.value2 != 0.0 ? " selected" : " unselected") + ", it is not");
      std::printf("editor: as expected, %s is %s\n", c.text.c_str(), selected ? "selected" : "unselected");
      break;
    }
    case CommandKind::ExpectParam: {
      if (view_.picked < 0) return fail("expect " + c.text + ": no object is picked");
      const ObjectRow& row = session_->rows()[size_t(view_.picked)];
      const double v = c.text == "K" ? row.K : c.text == "Q" ? row.Q : row.I;
      if (std::fabs(v - c.value) > 1e-5 * std::max(1.0, std::fabs(c.value)))
        return fail("expected " + row.name + "'s " + c.text + " = " + std::to_string(c.value) + ", it is " + std::to_string(v));
      std::printf("editor: as expected, %s's %s is %g\n", row.name.c_str(), c.text.c_str(), v);
      break;
    }
  }
  apply(r);
}

void EditorApp::printStats() const {
  const std::vector<FrameTiming>& timings = session_->allTimings();
  std::printf("editor: %llu frames; median ms per pass over them:\n", (unsigned long long)frames_);
  for (size_t p = 0; p < kPassCount; ++p) {
    std::vector<double> ms;
    for (const FrameTiming& t : timings)
      if (t.passMs[p]) ms.push_back(*t.passMs[p]);
    if (!ms.empty()) std::printf("  %-14s %8.2f\n", passName(Pass(p)), median(ms));
  }
  std::printf("  %-14s %8.2f (GPU; an empty timestamp bracket: %.2f)\n  %-14s %8.2f (CPU: ImGui's frame and panels)\n  %-14s %8.2f (wall)\n", "ui", median(uiGpuMs_), median(emptyBracketMs_), "ui",
              median(uiCpuMs_), "frame", median(frameMs_));
}

}  // namespace raybudget::editor
