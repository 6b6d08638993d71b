#include "render/WindowRenderer.h"

#include <algorithm>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "image/Image.h"
#include "render/ImageReadback.h"
#include "render/RenderPass.h"
#include "render/VulkanContext.h"

namespace rad {
namespace {

bool isSrgb(VkFormat f) {
    return f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_R8G8B8A8_SRGB ||
           f == VK_FORMAT_A8B8G8R8_SRGB_PACK32;
}

VkSurfaceFormatKHR chooseFormat(VkPhysicalDevice pd, VkSurfaceKHR surface) {
    std::uint32_t count = 0;
    vkCheck(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &count, nullptr),
            "vkGetPhysicalDeviceSurfaceFormatsKHR");
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkCheck(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &count, formats.data()),
            "vkGetPhysicalDeviceSurfaceFormatsKHR");
    if (formats.empty()) throw std::runtime_error("the window surface offers no formats");
    for (VkFormat want : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB})
        for (const auto& f : formats)
            if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
    for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
        for (const auto& f : formats)
            if (f.format == want) return f;
    return formats.front();
}

}  // namespace

WindowRenderer::WindowRenderer(const VulkanContext& context, VkSurfaceKHR surface,
                               std::function<VkExtent2D()> framebufferSize)
    : context_(context),
      surface_(surface),
      framebufferSize_(std::move(framebufferSize)),
      format_(chooseFormat(context.physicalDevice(), surface)),
      renderPass_(createColorDepthRenderPass(context.device(), format_.format, kDepthFormat,
                                             VK_IMAGE_LAYOUT_PRESENT_SRC_KHR)),
      commandPool_(context.device(), context.queueFamily()) {
    for (Frame& f : frames_) {
        f.cmd = commandPool_.allocate();
        f.done = Fence(context.device(), true);  // signalled: the first wait finds it free
        f.imageAvailable = createSemaphore(context.device());
    }
    createSwapchain();
}

WindowRenderer::~WindowRenderer() {
    // Unchecked: a destructor has no one to report to. The members go after
    // this, in reverse order: framebuffers and views before the swapchain and
    // the render pass.
    std::lock_guard lock(context_.queueMutex());
    vkDeviceWaitIdle(context_.device());
}

bool WindowRenderer::srgb() const { return isSrgb(format_.format); }

void WindowRenderer::waitIdle() const {
    std::lock_guard lock(context_.queueMutex());
    vkCheck(vkDeviceWaitIdle(context_.device()), "vkDeviceWaitIdle");
}

void WindowRenderer::destroySwapchain() {
    // The swapchain itself stays: the next one is created from it (oldSwapchain).
    framebuffers_.clear();
    views_.clear();
    depth_ = GpuImage();
    renderFinished_.clear();
    imageFences_.clear();
    images_.clear();
}

void WindowRenderer::createSwapchain() {
    VkDevice device = context_.device();
    VkSurfaceCapabilitiesKHR caps{};
    vkCheck(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physicalDevice(), surface_, &caps),
            "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == std::numeric_limits<std::uint32_t>::max()) {
        extent = framebufferSize_();
        extent.width = std::clamp(extent.width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height =
            std::clamp(extent.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    if (extent.width == 0 || extent.height == 0) {  // minimised: try again later
        extent_ = {0, 0};
        needsRecreate_ = true;
        return;
    }
    std::uint32_t imageCount = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);
    captureSupported_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;

    auto info = vkStruct<VkSwapchainCreateInfoKHR>(VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR);
    info.surface = surface_;
    info.minImageCount = imageCount;
    info.imageFormat = format_.format;
    info.imageColorSpace = format_.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                      (captureSupported_ ? VkImageUsageFlags{VK_IMAGE_USAGE_TRANSFER_SRC_BIT} : VkImageUsageFlags{0});
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
                            ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                            : caps.currentTransform;
    info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR;
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always supported
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_.get();
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    vkCheck(vkCreateSwapchainKHR(device, &info, nullptr, &swapchain), "vkCreateSwapchainKHR");
    swapchain_ = UniqueSwapchain(device, swapchain);  // destroys the old one
    extent_ = extent;
    minImageCount_ = std::max(caps.minImageCount, 2u);

    std::uint32_t count = 0;
    vkCheck(vkGetSwapchainImagesKHR(device, swapchain, &count, nullptr), "vkGetSwapchainImagesKHR");
    images_.resize(count);
    vkCheck(vkGetSwapchainImagesKHR(device, swapchain, &count, images_.data()),
            "vkGetSwapchainImagesKHR");
    depth_ = GpuImage(context_, extent.width, extent.height, kDepthFormat,
                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    for (VkImage image : images_) {
        views_.push_back(createImageView(device, image, format_.format, VK_IMAGE_ASPECT_COLOR_BIT));
        framebuffers_.push_back(
            createFramebuffer(device, renderPass_.get(), views_.back().get(), depth_.view(), extent));
        renderFinished_.push_back(createSemaphore(device));
    }
    imageFences_.assign(images_.size(), VK_NULL_HANDLE);
    needsRecreate_ = false;
    ++generation_;
}

VkCommandBuffer WindowRenderer::beginFrame(const std::array<float, 4>& clearColor) {
    // Set up: a swapchain of the window's size.
    const VkExtent2D wanted = framebufferSize_();
    if (wanted.width == 0 || wanted.height == 0) return VK_NULL_HANDLE;
    if (needsRecreate_ || !swapchain_ || wanted.width != extent_.width ||
        wanted.height != extent_.height) {
        waitIdle();
        destroySwapchain();
        createSwapchain();
        if (extent_.width == 0) return VK_NULL_HANDLE;
    }

    // A free frame slot and an image to draw into.
    Frame& frame = frames_[frameIndex_];
    frame.done.wait();
    finished_ = std::max(finished_, frame.serial);  // the queue runs frames in order
    frame.keepAlive.reset();
    const VkResult acquired =
        vkAcquireNextImageKHR(context_.device(), swapchain_.get(), UINT64_MAX, frame.imageAvailable.get(),
                              VK_NULL_HANDLE, &currentImage_);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
        needsRecreate_ = true;
        return VK_NULL_HANDLE;
    }
    vkCheck(acquired, "vkAcquireNextImageKHR");
    if (acquired == VK_SUBOPTIMAL_KHR) needsRecreate_ = true;  // present this one, then recreate
    // The image may still be in use by the other frame slot's commands.
    const VkFence fence = frame.done.get();
    if (VkFence previous = imageFences_[currentImage_]; previous != VK_NULL_HANDLE && previous != fence)
        vkCheck(vkWaitForFences(context_.device(), 1, &previous, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    imageFences_[currentImage_] = fence;

    // Draw: the caller records into the open render pass.
    beginRecording(frame.cmd);
    beginColorDepthPass(frame.cmd, renderPass_.get(), framebuffers_[currentImage_].get(), extent_, clearColor);
    return frame.cmd;
}

std::uint64_t WindowRenderer::endFrame(std::shared_ptr<const void> keepAlive, const std::string& capturePath) {
    Frame& frame = frames_[frameIndex_];
    VkCommandBuffer cmd = frame.cmd;
    vkCmdEndRenderPass(cmd);

    std::optional<ImageReadback> capture;
    if (!capturePath.empty()) {
        if (!captureSupported_)
            throw std::runtime_error("the window surface does not allow reading its images back");
        capture.emplace(context_, extent_, 4);
        capture->record(cmd, images_[currentImage_], VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    }
    endRecording(cmd);

    // Submit after the image is acquired; present after the commands are done.
    frame.done.reset();
    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    const VkSemaphore imageAvailable = frame.imageAvailable.get();
    const VkSemaphore rendered = renderFinished_[currentImage_].get();
    auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &imageAvailable;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &rendered;
    context_.submit(submit, frame.done.get());
    frame.keepAlive = std::move(keepAlive);
    frame.serial = ++submitted_;

    const VkSwapchainKHR swapchain = swapchain_.get();
    auto present = vkStruct<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &rendered;
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain;
    present.pImageIndices = &currentImage_;
    VkResult presented;
    {
        std::lock_guard lock(context_.queueMutex());
        presented = vkQueuePresentKHR(context_.queue(), &present);
    }
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR)
        needsRecreate_ = true;
    else
        vkCheck(presented, "vkQueuePresentKHR");
    frameIndex_ = (frameIndex_ + 1) % kFramesInFlight;

    if (capture) {
        frame.done.wait();
        finished_ = frame.serial;
        writeCapture(capturePath, capture->data());
    }
    return frame.serial;
}

void WindowRenderer::writeCapture(const std::string& path, const void* pixels) const {
    // The swapchain's bytes are what the window shows, sRGB-encoded already:
    // only the channel order and alpha go.
    Rgb8Image image;
    image.width = static_cast<int>(extent_.width);
    image.height = static_cast<int>(extent_.height);
    const std::size_t count = std::size_t{extent_.width} * extent_.height;
    image.rgb.resize(count * 3);
    const auto* src = static_cast<const unsigned char*>(pixels);
    const bool bgra = format_.format == VK_FORMAT_B8G8R8A8_SRGB ||
                      format_.format == VK_FORMAT_B8G8R8A8_UNORM;
    for (std::size_t i = 0; i < count; ++i) {
        image.rgb[3 * i + 0] = src[4 * i + (bgra ? 2 : 0)];
        image.rgb[3 * i + 1] = src[4 * i + 1];
        image.rgb[3 * i + 2] = src[4 * i + (bgra ? 0 : 2)];
    }
    writePng(image, path);
}

}  // namespace rad
