#include "render/WindowRenderer.h"

#include <algorithm>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "image/Image.h"
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

UniqueRenderPass createRenderPass(VkDevice device, VkFormat colorFormat) {
    std::array<VkAttachmentDescription, 2> attachments{};
    VkAttachmentDescription& color = attachments[0];
    color.format = colorFormat;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentDescription& depth = attachments[1];
    depth.format = WindowRenderer::kDepthFormat;
    depth.samples = VK_SAMPLE_COUNT_1_BIT;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    depth.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;

    const VkAttachmentReference colorRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference depthRef{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &colorRef;
    subpass.pDepthStencilAttachment = &depthRef;

    // The acquired image is written only after the acquire semaphore (waited
    // at colour output); the shared depth image only after the previous
    // frame's depth tests.
    VkSubpassDependency dep{};
    dep.srcSubpass = VK_SUBPASS_EXTERNAL;
    dep.dstSubpass = 0;
    dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                       VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dep.srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                       VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                       VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;

    auto info = vkStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    info.attachmentCount = static_cast<std::uint32_t>(attachments.size());
    info.pAttachments = attachments.data();
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 1;
    info.pDependencies = &dep;
    VkRenderPass pass = VK_NULL_HANDLE;
    vkCheck(vkCreateRenderPass(device, &info, nullptr, &pass), "vkCreateRenderPass");
    return {device, pass};
}

VkSemaphore createSemaphore(VkDevice device) {
    auto info = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    VkSemaphore s = VK_NULL_HANDLE;
    vkCheck(vkCreateSemaphore(device, &info, nullptr, &s), "vkCreateSemaphore");
    return s;
}

}  // namespace

WindowRenderer::WindowRenderer(const VulkanContext& context, VkSurfaceKHR surface,
                               std::function<VkExtent2D()> framebufferSize)
    : context_(context), surface_(surface), framebufferSize_(std::move(framebufferSize)) {
    VkDevice device = context.device();
    format_ = chooseFormat(context.physicalDevice(), surface);
    renderPass_ = createRenderPass(device, format_.format);

    auto poolInfo = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily();
    VkCommandPool pool = VK_NULL_HANDLE;
    vkCheck(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), "vkCreateCommandPool");
    commandPool_ = UniqueCommandPool(device, pool);

    for (Frame& f : frames_) {
        auto alloc =
            vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        alloc.commandPool = pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        vkCheck(vkAllocateCommandBuffers(device, &alloc, &f.cmd), "vkAllocateCommandBuffers");
        auto fenceInfo = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT;
        VkFence fence = VK_NULL_HANDLE;
        vkCheck(vkCreateFence(device, &fenceInfo, nullptr, &fence), "vkCreateFence");
        f.fence = UniqueFence(device, fence);
        f.imageAvailable = createSemaphore(device);
    }
    createSwapchain();
}

WindowRenderer::~WindowRenderer() {
    waitIdle();
    destroySwapchain();
    if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
    for (Frame& f : frames_) {
        f.keepAlive.reset();
        if (f.imageAvailable != VK_NULL_HANDLE)
            vkDestroySemaphore(context_.device(), f.imageAvailable, nullptr);
    }
}

bool WindowRenderer::srgb() const { return isSrgb(format_.format); }

void WindowRenderer::waitIdle() const {
    std::lock_guard lock(context_.queueMutex());
    vkDeviceWaitIdle(context_.device());
}

void WindowRenderer::destroySwapchain() {
    VkDevice device = context_.device();
    framebuffers_.clear();
    views_.clear();
    depth_ = GpuImage();
    for (VkSemaphore s : renderFinished_) vkDestroySemaphore(device, s, nullptr);
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
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    vkCheck(vkCreateSwapchainKHR(device, &info, nullptr, &swapchain), "vkCreateSwapchainKHR");
    if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(device, swapchain_, nullptr);
    swapchain_ = swapchain;
    extent_ = extent;
    minImageCount_ = std::max(caps.minImageCount, 2u);

    std::uint32_t count = 0;
    vkCheck(vkGetSwapchainImagesKHR(device, swapchain_, &count, nullptr), "vkGetSwapchainImagesKHR");
    images_.resize(count);
    vkCheck(vkGetSwapchainImagesKHR(device, swapchain_, &count, images_.data()),
            "vkGetSwapchainImagesKHR");
    depth_ = GpuImage(context_, extent.width, extent.height, kDepthFormat,
                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    for (VkImage image : images_) {
        auto viewInfo = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
        viewInfo.image = image;
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = format_.format;
        viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        vkCheck(vkCreateImageView(device, &viewInfo, nullptr, &view), "vkCreateImageView");
        views_.emplace_back(device, view);

        const std::array<VkImageView, 2> attachments{view, depth_.view()};
        auto fbInfo = vkStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
        fbInfo.renderPass = renderPass_.get();
        fbInfo.attachmentCount = static_cast<std::uint32_t>(attachments.size());
        fbInfo.pAttachments = attachments.data();
        fbInfo.width = extent.width;
        fbInfo.height = extent.height;
        fbInfo.layers = 1;
        VkFramebuffer fb = VK_NULL_HANDLE;
        vkCheck(vkCreateFramebuffer(device, &fbInfo, nullptr, &fb), "vkCreateFramebuffer");
        framebuffers_.emplace_back(device, fb);
        renderFinished_.push_back(createSemaphore(device));
    }
    imageFences_.assign(images_.size(), VK_NULL_HANDLE);
    needsRecreate_ = false;
    ++generation_;
}

VkCommandBuffer WindowRenderer::beginFrame(const std::array<float, 4>& clearColor) {
    VkDevice device = context_.device();
    const VkExtent2D wanted = framebufferSize_();
    if (wanted.width == 0 || wanted.height == 0) return VK_NULL_HANDLE;
    if (needsRecreate_ || swapchain_ == VK_NULL_HANDLE || wanted.width != extent_.width ||
        wanted.height != extent_.height) {
        waitIdle();
        destroySwapchain();
        createSwapchain();
        if (extent_.width == 0) return VK_NULL_HANDLE;
    }

    Frame& frame = frames_[frameIndex_];
    VkFence fence = frame.fence.get();
    vkCheck(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    frame.keepAlive.reset();

    const VkResult acquired = vkAcquireNextImageKHR(device, swapchain_, UINT64_MAX,
                                                    frame.imageAvailable, VK_NULL_HANDLE,
                                                    &currentImage_);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
        needsRecreate_ = true;
        return VK_NULL_HANDLE;
    }
    vkCheck(acquired, "vkAcquireNextImageKHR");
    if (acquired == VK_SUBOPTIMAL_KHR) needsRecreate_ = true;  // present this one, then recreate
    if (VkFence previous = imageFences_[currentImage_]; previous != VK_NULL_HANDLE && previous != fence)
        vkCheck(vkWaitForFences(device, 1, &previous, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    imageFences_[currentImage_] = fence;

    VkCommandBuffer cmd = frame.cmd;
    vkCheck(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkCheck(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    std::array<VkClearValue, 2> clears{};
    clears[0].color = {{clearColor[0], clearColor[1], clearColor[2], clearColor[3]}};
    clears[1].depthStencil = {1.0f, 0};
    auto pass = vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    pass.renderPass = renderPass_.get();
    pass.framebuffer = framebuffers_[currentImage_].get();
    pass.renderArea = {{0, 0}, extent_};
    pass.clearValueCount = static_cast<std::uint32_t>(clears.size());
    pass.pClearValues = clears.data();
    vkCmdBeginRenderPass(cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
    return cmd;
}

void WindowRenderer::endFrame(std::shared_ptr<const void> keepAlive, const std::string& capturePath) {
    Frame& frame = frames_[frameIndex_];
    VkCommandBuffer cmd = frame.cmd;
    vkCmdEndRenderPass(cmd);

    GpuBuffer capture;
    const bool capturing = !capturePath.empty();
    if (capturing) {
        if (!captureSupported_)
            throw std::runtime_error("the window surface does not allow reading its images back");
        const VkImage image = images_[currentImage_];
        capture = GpuBuffer(context_, VkDeviceSize{4} * extent_.width * extent_.height,
                            VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        auto toCopy = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        toCopy.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        toCopy.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        toCopy.oldLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        toCopy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        toCopy.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        toCopy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        toCopy.image = image;
        toCopy.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toCopy);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {extent_.width, extent_.height, 1};
        vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, capture.buffer(), 1,
                               &region);
        auto back = toCopy;
        back.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        back.dstAccessMask = 0;
        back.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        back.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        auto toHost = vkStruct<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
        toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        toHost.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        toHost.buffer = capture.buffer();
        toHost.size = VK_WHOLE_SIZE;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                             nullptr, 1, &toHost, 1, &back);
    }
    vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

    VkFence fence = frame.fence.get();
    vkCheck(vkResetFences(context_.device(), 1, &fence), "vkResetFences");
    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSemaphore done = renderFinished_[currentImage_];
    auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &frame.imageAvailable;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &done;
    context_.submit(submit, fence);
    frame.keepAlive = std::move(keepAlive);

    auto present = vkStruct<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &done;
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain_;
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

    if (capturing) {
        vkCheck(vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        writeCapture(capturePath, capture);
    }
}

void WindowRenderer::writeCapture(const std::string& path, const GpuBuffer& buffer) const {
    // The swapchain holds sRGB-encoded bytes already (an *_SRGB format, or
    // the shader encodes for UNORM): only the channel order and alpha go.
    Rgb8Image image;
    image.width = static_cast<int>(extent_.width);
    image.height = static_cast<int>(extent_.height);
    const std::size_t pixels = std::size_t{extent_.width} * extent_.height;
    image.rgb.resize(pixels * 3);
    const auto* src = static_cast<const unsigned char*>(buffer.mapped());
    const bool bgra = format_.format == VK_FORMAT_B8G8R8A8_SRGB ||
                      format_.format == VK_FORMAT_B8G8R8A8_UNORM;
    for (std::size_t i = 0; i < pixels; ++i) {
        image.rgb[3 * i + 0] = src[4 * i + (bgra ? 2 : 0)];
        image.rgb[3 * i + 1] = src[4 * i + 1];
        image.rgb[3 * i + 2] = src[4 * i + (bgra ? 0 : 2)];
    }
    writePng(image, path);
}

}  // namespace rad
