#pragma once
// Reading a rendered colour image back to the host: a mapped buffer the size of
// the image, and the commands that copy the image into it.
//
//   ImageReadback readback(context, extent, 4 * sizeof(float));
//   ... render pass (createColorDepthRenderPass) ...
//   readback.record(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
//   ... submit, wait for the fence ...
//   const auto* pixels = static_cast<const float*>(readback.data());

#include <vulkan/vulkan.h>

#include <cstdint>

#include "render/GpuResources.h"

namespace rad {

class VulkanContext;

class ImageReadback {
  public:
    ImageReadback(const VulkanContext& context, VkExtent2D extent, std::uint32_t bytesPerPixel);

    // Records, after the render pass that left `image` in `layout`, the copy
    // of the whole image and a barrier that makes it visible to the host. An
    // image in another layout than TRANSFER_SRC_OPTIMAL (a swapchain image in
    // PRESENT_SRC_KHR) is moved there for the copy and back afterwards.
    void record(VkCommandBuffer cmd, VkImage image, VkImageLayout layout) const;

    // Rows top first, tightly packed; valid once the commands have completed.
    const void* data() const { return buffer_.mapped(); }
    VkExtent2D extent() const { return extent_; }

  private:
    GpuBuffer buffer_;
    VkExtent2D extent_{0, 0};
};

}  // namespace rad
