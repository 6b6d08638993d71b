#include "render/OffscreenRenderer.h"

#include <array>
#include <stdexcept>
#include <string>

#include "render/VulkanContext.h"
#include "radiosity/Snapshot.h"

namespace rad {
namespace {

void requireFormat(VkPhysicalDevice pd, VkFormat format, VkFormatFeatureFlags features,
                   const char* what) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(pd, format, &props);
    if ((props.optimalTilingFeatures & features) != features)
        throw std::runtime_error(std::string("the Vulkan device cannot use ") + what +
                                 " for offscreen rendering");
}

UniqueRenderPass createRenderPass(VkDevice device) {
    std::array<VkAttachmentDescription, 2> attachments{};
    VkAttachmentDescription& color = attachments[0];
    color.format = OffscreenRenderer::kColorFormat;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // cleared anyway
    color.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkAttachmentDescription& depth = attachments[1];
    depth.format = OffscreenRenderer::kDepthFormat;
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

    // The attachments are reused frame after frame: this frame's clear and
    // writes must wait for the previous frame's copy-out and depth tests, and
    // the copy-out after this pass must wait for the colour writes.
    std::array<VkSubpassDependency, 2> dependencies{};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask =
        VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                   VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                   VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;

    auto info = vkStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    info.attachmentCount = static_cast<std::uint32_t>(attachments.size());
    info.pAttachments = attachments.data();
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = static_cast<std::uint32_t>(dependencies.size());
    info.pDependencies = dependencies.data();
    VkRenderPass pass = VK_NULL_HANDLE;
    vkCheck(vkCreateRenderPass(device, &info, nullptr, &pass), "vkCreateRenderPass");
    return {device, pass};
}

}  // namespace

OffscreenRenderer::OffscreenRenderer(const VulkanContext& context) : context_(context) {
    VkDevice device = context.device();
    requireFormat(context.physicalDevice(), kColorFormat,
                  VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT,
                  "R32G32B32A32_SFLOAT colour");
    requireFormat(context.physicalDevice(), kDepthFormat,
                  VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT, "D32_SFLOAT depth");
    renderPass_ = createRenderPass(device);
    meshRenderer_.emplace(context, renderPass_.get());

    auto poolInfo = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily();
    VkCommandPool pool = VK_NULL_HANDLE;
    vkCheck(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), "vkCreateCommandPool");
    commandPool_ = UniqueCommandPool(device, pool);

    auto alloc =
        vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    vkCheck(vkAllocateCommandBuffers(device, &alloc, &commandBuffer_), "vkAllocateCommandBuffers");

    auto fenceInfo = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    VkFence fence = VK_NULL_HANDLE;
    vkCheck(vkCreateFence(device, &fenceInfo, nullptr, &fence), "vkCreateFence");
    fence_ = UniqueFence(device, fence);
}

void OffscreenRenderer::ensureTarget(std::uint32_t width, std::uint32_t height) {
    if (target_ && target_->width == width && target_->height == height) return;
    target_.reset();  // the fence wait in render() guarantees the old one is idle

    Target t;
    t.width = width;
    t.height = height;
    t.color = GpuImage(context_, width, height, kColorFormat,
                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                       VK_IMAGE_ASPECT_COLOR_BIT);
    t.depth = GpuImage(context_, width, height, kDepthFormat,
                       VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    const std::array<VkImageView, 2> views{t.color.view(), t.depth.view()};
    auto info = vkStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
    info.renderPass = renderPass_.get();
    info.attachmentCount = static_cast<std::uint32_t>(views.size());
    info.pAttachments = views.data();
    info.width = width;
    info.height = height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    vkCheck(vkCreateFramebuffer(context_.device(), &info, nullptr, &framebuffer),
            "vkCreateFramebuffer");
    t.framebuffer = UniqueFramebuffer(context_.device(), framebuffer);
    t.readback = GpuBuffer(context_, VkDeviceSize{4} * sizeof(float) * width * height,
                           VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    target_ = std::move(t);
}

Image OffscreenRenderer::render(const MeshSnapshot& snapshot, const glm::mat4& viewProjection,
                                int width, int height, const MeshDrawOptions& options) {
    const GpuMesh mesh(context_, snapshot);
    return render(mesh, viewProjection, width, height, options);
}

Image OffscreenRenderer::render(const GpuMesh& mesh, const glm::mat4& viewProjection, int width,
                                int height, const MeshDrawOptions& options) {
    const auto maxSize = static_cast<int>(context_.properties().limits.maxImageDimension2D);
    if (width < 1 || height < 1 || width > maxSize || height > maxSize)
        throw std::runtime_error("offscreen image size " + std::to_string(width) + "x" +
                                 std::to_string(height) + " is outside 1.." +
                                 std::to_string(maxSize));
    const auto w = static_cast<std::uint32_t>(width);
    const auto h = static_cast<std::uint32_t>(height);
    ensureTarget(w, h);

    VkCommandBuffer cmd = commandBuffer_;
    vkCheck(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkCheck(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");

    std::array<VkClearValue, 2> clears{};
    clears[0].color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    clears[1].depthStencil = {1.0f, 0};
    auto pass = vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    pass.renderPass = renderPass_.get();
    pass.framebuffer = target_->framebuffer.get();
    pass.renderArea = {{0, 0}, {w, h}};
    pass.clearValueCount = static_cast<std::uint32_t>(clears.size());
    pass.pClearValues = clears.data();
    vkCmdBeginRenderPass(cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
    meshRenderer_->draw(cmd, mesh, viewProjection, {w, h}, options);
    vkCmdEndRenderPass(cmd);

    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {w, h, 1};
    vkCmdCopyImageToBuffer(cmd, target_->color.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           target_->readback.buffer(), 1, &copy);
    // Make the copy visible to the host reads below.
    auto toHost = vkStruct<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
    toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    toHost.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toHost.buffer = target_->readback.buffer();
    toHost.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                         nullptr, 1, &toHost, 0, nullptr);
    vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

    VkFence fence = fence_.get();
    vkCheck(vkResetFences(context_.device(), 1, &fence), "vkResetFences");
    auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    context_.submit(submit, fence);
    vkCheck(vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");

    // RGBA rows, top first, tightly packed: drop alpha.
    Image image;
    image.width = width;
    image.height = height;
    image.rgb.resize(static_cast<std::size_t>(width) * height * 3);
    const auto* rgba = static_cast<const float*>(target_->readback.mapped());
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) image.rgb[3 * i + c] = rgba[4 * i + c];
    return image;
}

}  // namespace rad
