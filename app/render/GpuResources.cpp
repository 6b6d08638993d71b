#include "render/GpuResources.h"

#include <algorithm>

#include <cstring>
#include <stdexcept>

#include "render/VulkanContext.h"

namespace rad {

VkImageMemoryBarrier colorLayoutBarrier(VkImage image, VkImageLayout from, VkImageLayout to, std::uint32_t layers) {
    auto barrier = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
    return barrier;
}

UniqueMemory allocateMemory(const VulkanContext& context, const VkMemoryRequirements& req,
                            VkMemoryPropertyFlags properties) {
    auto alloc = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = context.findMemoryType(req.memoryTypeBits, properties);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    vkCheck(vkAllocateMemory(context.device(), &alloc, nullptr, &memory), "vkAllocateMemory");
    return UniqueMemory(context.device(), memory);
}

UniqueImageView createImageView(VkDevice device, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                                std::uint32_t arrayLayers) {
    auto info = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    info.image = image;
    info.viewType = arrayLayers > 0 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    info.format = format;
    info.subresourceRange = {aspect, 0, 1, 0, std::max<std::uint32_t>(arrayLayers, 1)};
    VkImageView view = VK_NULL_HANDLE;
    vkCheck(vkCreateImageView(device, &info, nullptr, &view), "vkCreateImageView");
    return {device, view};
}

GpuBuffer::GpuBuffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage)
    : size_(size) {
    VkDevice device = context.device();
    auto info = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    vkCheck(vkCreateBuffer(device, &info, nullptr, &buffer), "vkCreateBuffer");
    buffer_ = UniqueBuffer(device, buffer);

    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, buffer, &req);
    memory_ = allocateMemory(
        context, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    VkDeviceMemory memory = memory_.get();
    vkCheck(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
    vkCheck(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
}

void GpuBuffer::write(const void* data, std::size_t bytes) {
    if (bytes > size_) throw std::runtime_error("GpuBuffer::write: data larger than the buffer");
    if (bytes > 0) std::memcpy(mapped_, data, bytes);
}

GpuImage::GpuImage(const VulkanContext& context, std::uint32_t width, std::uint32_t height,
                   VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                   std::uint32_t arrayLayers)
    : format_(format) {
    VkDevice device = context.device();
    auto info = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = std::max<std::uint32_t>(arrayLayers, 1);
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    vkCheck(vkCreateImage(device, &info, nullptr, &image), "vkCreateImage");
    image_ = UniqueImage(device, image);

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    memory_ = allocateMemory(context, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    vkCheck(vkBindImageMemory(device, image, memory_.get(), 0), "vkBindImageMemory");

    view_ = createImageView(device, image, format, aspect, arrayLayers);
}

}  // namespace rad
