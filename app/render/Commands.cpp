#include "render/Commands.h"

namespace rad {

CommandPool::CommandPool(VkDevice device, std::uint32_t queueFamily, VkCommandPoolCreateFlags flags)
    : device_(device) {
    auto info = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    info.flags = flags;
    info.queueFamilyIndex = queueFamily;
    VkCommandPool pool = VK_NULL_HANDLE;
    vkCheck(vkCreateCommandPool(device, &info, nullptr, &pool), "vkCreateCommandPool");
    pool_ = UniqueCommandPool(device, pool);
}

VkCommandBuffer CommandPool::allocate() const {
    auto info = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    info.commandPool = pool_.get();
    info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    info.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    vkCheck(vkAllocateCommandBuffers(device_, &info, &cmd), "vkAllocateCommandBuffers");
    return cmd;
}

void beginRecording(VkCommandBuffer cmd) {
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkCheck(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
}

void endRecording(VkCommandBuffer cmd) { vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer"); }

Fence::Fence(VkDevice device, bool signaled) : device_(device) {
    auto info = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    if (signaled) info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkFence fence = VK_NULL_HANDLE;
    vkCheck(vkCreateFence(device, &info, nullptr, &fence), "vkCreateFence");
    fence_ = UniqueFence(device, fence);
}

void Fence::wait() const {
    const VkFence fence = fence_.get();
    vkCheck(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

void Fence::reset() {
    const VkFence fence = fence_.get();
    vkCheck(vkResetFences(device_, 1, &fence), "vkResetFences");
}

UniqueSemaphore createSemaphore(VkDevice device) {
    auto info = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    VkSemaphore semaphore = VK_NULL_HANDLE;
    vkCheck(vkCreateSemaphore(device, &info, nullptr, &semaphore), "vkCreateSemaphore");
    return {device, semaphore};
}

}  // namespace rad
