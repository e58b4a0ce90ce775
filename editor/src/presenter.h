// What the editor shows: a canvas image the size of the window, into which each frame the
// viewport is copied and the UI drawn (a render pass loading the canvas), then blitted to
// the acquired swapchain image and presented. Screenshots read the canvas, so they show
// exactly what was presented. The swapchain is rebuilt when the window's size changes.
#pragma once
#include <cstdint>
#include <vector>

#include "window_device.h"

namespace raybudget::editor {

class Presenter {
 public:
  static constexpr VkFormat kCanvasFormat = VK_FORMAT_R8G8B8A8_UNORM;

  explicit Presenter(const WindowDevice& wd);
  ~Presenter();

  VkRenderPass uiRenderPass() const { return renderPass_; }
  VkFramebuffer canvasFramebuffer() const { return framebuffer_; }
  VkImage canvas() const { return canvas_.image; }
  VkExtent2D extent() const { return canvas_.extent; }
  uint32_t imageCount() const { return uint32_t(images_.size()); }
  uint32_t minImageCount() const { return minImageCount_; }

  // Acquires the next swapchain image, signalling `acquired`; false when the swapchain had
  // to be rebuilt (the window changed size): skip this frame.
  bool acquire(VkSemaphore acquired, uint32_t& imageIndex);
  // Records the canvas (TRANSFER_SRC_OPTIMAL) blitted into swapchain image `imageIndex`,
  // left ready to present.
  void recordBlitToSwapchain(VkCommandBuffer cmd, uint32_t imageIndex) const;
  // The semaphore a frame presenting `imageIndex` signals and the present waits on.
  VkSemaphore renderDone(uint32_t imageIndex) const { return renderDone_[imageIndex]; }
  void present(uint32_t imageIndex);

 private:
  void build();

  const WindowDevice& wd_;
  Owned<VkRenderPass> renderPass_;
  Owned<VkSwapchainKHR> swapchain_;
  std::vector<VkImage> images_;
  std::vector<Owned<VkSemaphore>> renderDone_;
  DeviceImage canvas_;
  Owned<VkFramebuffer> framebuffer_;
  VkFormat swapchainFormat_ = VK_FORMAT_UNDEFINED;
  uint32_t minImageCount_ = 2;
};

}  // namespace raybudget::editor
