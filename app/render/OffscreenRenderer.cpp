#include "render/OffscreenRenderer.h"

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

VkExtent2D checkedExtent(const VulkanContext& context, int width, int height) {
    const auto maxSize = static_cast<int>(context.properties().limits.maxImageDimension2D);
    if (width < 1 || height < 1 || width > maxSize || height > maxSize)
        throw std::runtime_error("offscreen image size " + std::to_string(width) + "x" +
                                 std::to_string(height) + " is outside 1.." +
                                 std::to_string(maxSize));
    return {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)};
}

// RGBA float rows, top first, tightly packed: alpha dropped.
Image toImage(const ImageReadback& readback) {
    Image image;
    image.width = static_cast<int>(readback.extent().width);
    image.height = static_cast<int>(readback.extent().height);
    const std::size_t pixels = std::size_t{readback.extent().width} * readback.extent().height;
    image.rgb.resize(pixels * 3);
    const auto* rgba = static_cast<const float*>(readback.data());
    for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) image.rgb[3 * i + c] = rgba[4 * i + c];
    return image;
}

}  // namespace

OffscreenRenderer::Target::Target(const VulkanContext& context, VkRenderPass renderPass, VkExtent2D size)
    : extent(size),
      color(context, size.width, size.height, kColorFormat,
            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT),
      depth(context, size.width, size.height, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
            VK_IMAGE_ASPECT_DEPTH_BIT),
      framebuffer(createFramebuffer(context.device(), renderPass, color.view(), depth.view(), size)),
      readback(context, size, 4 * sizeof(float)) {}

OffscreenRenderer::OffscreenRenderer(const VulkanContext& context, ShaderOutput output)
    : context_(context), commandPool_(context.device(), context.queueFamily()), frameDone_(context.device()) {
    requireFormat(context.physicalDevice(), kColorFormat,
                  VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT,
                  "R32G32B32A32_SFLOAT colour");
    requireFormat(context.physicalDevice(), kDepthFormat,
                  VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT, "D32_SFLOAT depth");
    renderPass_ = createColorDepthRenderPass(context.device(), kColorFormat, kDepthFormat,
                                             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    meshRenderer_.emplace(context, renderPass_.get(), output);
    commandBuffer_ = commandPool_.allocate();
}

Image OffscreenRenderer::render(const MeshSnapshot& snapshot, const glm::dmat4& viewProjection,
                                int width, int height, const MeshDrawOptions& options) {
    const GpuMesh mesh(context_, snapshot);
    if (!textures_ || !textures_->sameSources(snapshot.textures)) {
        textures_.reset();  // the old upload goes first: one copy in memory at a time
        textures_.emplace(context_, snapshot.textures);
    }
    return render(mesh, *textures_, viewProjection, width, height, options);
}

Image OffscreenRenderer::render(const GpuMesh& mesh, const GpuTextures& textures,
                                const glm::dmat4& viewProjection, int width, int height,
                                const MeshDrawOptions& options) {
    // Set up: attachments of this size (the fence wait of the previous
    // render() means the old ones are idle).
    const VkExtent2D extent = checkedExtent(context_, width, height);
    if (!target_ || target_->extent.width != extent.width || target_->extent.height != extent.height) {
        target_.reset();
        target_.emplace(context_, renderPass_.get(), extent);
    }

    // Draw, read back, wait.
    VkCommandBuffer cmd = commandBuffer_;
    beginRecording(cmd);
    beginColorDepthPass(cmd, renderPass_.get(), target_->framebuffer.get(), extent, {0.0f, 0.0f, 0.0f, 0.0f});
    meshRenderer_->draw(cmd, mesh, textures, viewProjection, extent, options);
    vkCmdEndRenderPass(cmd);
    target_->readback.record(cmd, target_->color.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    endRecording(cmd);
    frameDone_.reset();
    context_.submit(cmd, frameDone_.get());
    frameDone_.wait();
    return toImage(target_->readback);
}

}  // namespace rad
