#include "render/ImageReadback.h"

namespace rad {

ImageReadback::ImageReadback(const VulkanContext& context, VkExtent2D extent, std::uint32_t bytesPerPixel)
    : buffer_(context, VkDeviceSize{bytesPerPixel} * extent.width * extent.height, VK_BUFFER_USAGE_TRANSFER_DST_BIT),
      extent_(extent) {}

void ImageReadback::record(VkCommandBuffer cmd, VkImage image, VkImageLayout layout) const {
    const bool move = layout != VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    if (move) {
        // The render pass made the colour writes visible to transfers
        // (createColorDepthRenderPass): chain on its transfer stage.
        auto toCopy = colorLayoutBarrier(image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        toCopy.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        toCopy.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toCopy);
    }

    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent_.width, extent_.height, 1};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer_.buffer(), 1, &region);

    auto toHost = vkStruct<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
    toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    toHost.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toHost.buffer = buffer_.buffer();
    toHost.size = VK_WHOLE_SIZE;
    if (!move) {
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1,
                             &toHost, 0, nullptr);
        return;
    }
    // Moving back only has to wait for the copy's reads: no access to flush.
    const auto back = colorLayoutBarrier(image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
    const VkPipelineStageFlags after = VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, after, 0, 0, nullptr, 1, &toHost, 1, &back);
}

}  // namespace rad
