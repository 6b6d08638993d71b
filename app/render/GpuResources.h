#pragma once
// Buffers and images with their memory, owned together. Move-only; the
// VulkanContext they were made from must outlive them.

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>

#include "render/VkCheck.h"

namespace rad {

class VulkanContext;

// Memory of the given kind for a resource with these requirements.
UniqueMemory allocateMemory(const VulkanContext& context, const VkMemoryRequirements& req,
                            VkMemoryPropertyFlags properties);

// The barrier that moves the colour image's mip level 0, layers 0 to
// layers - 1, from one layout to another (no queue family transfer).
VkImageMemoryBarrier colorLayoutBarrier(VkImage image, VkImageLayout from, VkImageLayout to, std::uint32_t layers = 1);

// A view of mip level 0 of the image: 2D (layer 0) when arrayLayers is 0,
// else a 2D array of that many layers (a sampler2DArray, even of one).
UniqueImageView createImageView(VkDevice device, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                                std::uint32_t arrayLayers = 0);

// A buffer in host-visible, coherent memory, mapped for its whole life. Mesh
// data is small next to the cost of a solve, and lavapipe's memory is all
// host memory anyway, so staging to device-local memory is not worth it here.
class GpuBuffer {
  public:
    GpuBuffer() = default;
    GpuBuffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage);

    VkBuffer buffer() const { return buffer_.get(); }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }
    // Copies bytes to the start of the buffer (size must fit).
    void write(const void* data, std::size_t bytes);

  private:
    UniqueMemory memory_;
    UniqueBuffer buffer_;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;  // unmapped implicitly by vkFreeMemory
};

// A 2D image in device-local memory with one view: for attachments, or
// with arrayLayers > 0 an array of that many layers viewed as one (textures).
class GpuImage {
  public:
    GpuImage() = default;
    GpuImage(const VulkanContext& context, std::uint32_t width, std::uint32_t height,
             VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect,
             std::uint32_t arrayLayers = 0);

    VkImage image() const { return image_.get(); }
    VkImageView view() const { return view_.get(); }
    VkFormat format() const { return format_; }

  private:
    UniqueMemory memory_;
    UniqueImage image_;
    UniqueImageView view_;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
};

}  // namespace rad
