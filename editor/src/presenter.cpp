#include "presenter.h"

#include <algorithm>

#include <GLFW/glfw3.h>

namespace raybudget::editor {
namespace {

Owned<VkRenderPass> createUiRenderPass(VkDevice device) {
  // The canvas arrives with the viewport copied in (TRANSFER_DST) and leaves for the blit
  // and the screenshot copy (TRANSFER_SRC).
  VkAttachmentDescription colour{};
  colour.format = Presenter::kCanvasFormat;
  colour.samples = VK_SAMPLE_COUNT_1_BIT;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  colour.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  colour.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  VkSubpassDependency deps[2]{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  ci.attachmentCount = 1;
  ci.pAttachments = &colour;
  ci.subpassCount = 1;
  ci.pSubpasses = &subpass;
  ci.dependencyCount = 2;
  ci.pDependencies = deps;
  return make(device, vkCreateRenderPass, vkDestroyRenderPass, ci, "vkCreateRenderPass");
}

}  // namespace

Presenter::Presenter(const WindowDevice& wd) : wd_(wd) {
  renderPass_ = createUiRenderPass(wd.device());
  build();
}

Presenter::~Presenter() { vkDeviceWaitIdle(wd_.device()); }

void Presenter::build() {
  check(vkDeviceWaitIdle(wd_.device()), "vkDeviceWaitIdle");
  VkSurfaceCapabilitiesKHR caps;
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(wd_.physicalDevice(), wd_.surface(), &caps), "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT)) throw Error("editor: the window's swapchain images cannot be blitted to");
  uint32_t count = 0;
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(wd_.physicalDevice(), wd_.surface(), &count, nullptr), "vkGetPhysicalDeviceSurfaceFormatsKHR");
  std::vector<VkSurfaceFormatKHR> formats(count);
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(wd_.physicalDevice(), wd_.surface(), &count, formats.data()), "vkGetPhysicalDeviceSurfaceFormatsKHR");
  // A UNORM format: the canvas already holds sRGB-encoded values, which a blit into an
  // _SRGB image would encode a second time.
  VkSurfaceFormatKHR chosen = formats.at(0);
  for (const VkSurfaceFormatKHR& f : formats)
    if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) chosen = f;
  swapchainFormat_ = chosen.format;
  uint32_t modeCount = 0;
  check(vkGetPhysicalDeviceSurfacePresentModesKHR(wd_.physicalDevice(), wd_.surface(), &modeCount, nullptr), "vkGetPhysicalDeviceSurfacePresentModesKHR");
  std::vector<VkPresentModeKHR> modes(modeCount);
  check(vkGetPhysicalDeviceSurfacePresentModesKHR(wd_.physicalDevice(), wd_.surface(), &modeCount, modes.data()),
        "vkGetPhysicalDeviceSurfacePresentModesKHR");
  // Not tied to a display's refresh: the editor shows the renderer's own frame rate.
  VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;
  for (VkPresentModeKHR m : {VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR})
    if (std::find(modes.begin(), modes.end(), m) != modes.end()) mode = m;

  VkExtent2D extent = caps.currentExtent;
  if (extent.width == 0xFFFFFFFFu) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(wd_.window(), &w, &h);
    extent = {uint32_t(std::max(w, 1)), uint32_t(std::max(h, 1))};
  }
  extent.width = std::max(extent.width, 1u);
  extent.height = std::max(extent.height, 1u);
  minImageCount_ = std::max(2u, caps.minImageCount);
  uint32_t imageCount = caps.minImageCount + 1;
  if (caps.maxImageCount) imageCount = std::min(imageCount, caps.maxImageCount);

  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = wd_.surface();
  ci.minImageCount = imageCount;
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  ci.presentMode = mode;
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = swapchain_;
  Owned<VkSwapchainKHR> next = make(wd_.device(), vkCreateSwapchainKHR, vkDestroySwapchainKHR, ci, "vkCreateSwapchainKHR");
  swapchain_ = std::move(next);
  check(vkGetSwapchainImagesKHR(wd_.device(), swapchain_, &count, nullptr), "vkGetSwapchainImagesKHR");
  images_.resize(count);
  check(vkGetSwapchainImagesKHR(wd_.device(), swapchain_, &count, images_.data()), "vkGetSwapchainImagesKHR");
  renderDone_.clear();
  for (uint32_t i = 0; i < count; ++i) {
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    renderDone_.push_back(make(wd_.device(), vkCreateSemaphore, vkDestroySemaphore, si, "vkCreateSemaphore"));
  }

  framebuffer_.reset();
  canvas_ = createImage(wd_, kCanvasFormat, extent,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fi.renderPass = renderPass_;
  fi.attachmentCount = 1;
  fi.pAttachments = canvas_.view.ptr();
  fi.width = extent.width;
  fi.height = extent.height;
  fi.layers = 1;
  framebuffer_ = make(wd_.device(), vkCreateFramebuffer, vkDestroyFramebuffer, fi, "vkCreateFramebuffer");
}

bool Presenter::acquire(VkSemaphore acquired, uint32_t& imageIndex) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(wd_.window(), &w, &h);
  if (uint32_t(w) != canvas_.extent.width || uint32_t(h) != canvas_.extent.height) {
    if (w == 0 || h == 0) return false;  // minimised
    build();
    return false;
  }
  const VkResult r = vkAcquireNextImageKHR(wd_.device(), swapchain_, UINT64_MAX, acquired, VK_NULL_HANDLE, &imageIndex);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) {
    build();
    return false;
  }
  if (r != VK_SUBOPTIMAL_KHR) check(r, "vkAcquireNextImageKHR");
  return true;
}

void Presenter::recordBlitToSwapchain(VkCommandBuffer cmd, uint32_t imageIndex) const {
  const VkImage target = images_[imageIndex];
  imageBarrier(cmd, target, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
               VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  VkImageBlit blit{};
  blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = blit.dstOffsets[1] = {int32_t(canvas_.extent.width), int32_t(canvas_.extent.height), 1};
  vkCmdBlitImage(cmd, canvas_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
  imageBarrier(cmd, target, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
}

void Presenter::present(uint32_t imageIndex) {
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = renderDone_[imageIndex].ptr();
  pi.swapchainCount = 1;
  pi.pSwapchains = swapchain_.ptr();
  pi.pImageIndices = &imageIndex;
  const VkResult r = vkQueuePresentKHR(wd_.queue(), &pi);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) build();
  else check(r, "vkQueuePresentKHR");
}

}  // namespace raybudget::editor
