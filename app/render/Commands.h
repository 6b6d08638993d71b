#pragma once
// Recording command buffers and waiting for them: a command pool, fences and
// semaphores, owned (RAII) and checked (vkCheck) in one place.
//
//   CommandPool pool(device, queueFamily);
//   VkCommandBuffer cmd = pool.allocate();
//   Fence done(device);
//   beginRecording(cmd);  ...  endRecording(cmd);
//   context.submit(cmd, done.get());
//   done.wait();

#include <vulkan/vulkan.h>

#include <cstdint>

#include "render/VkCheck.h"

namespace rad {

class CommandPool {
  public:
    CommandPool() = default;  // empty, until one is moved in
    // The default lets each buffer be re-recorded (vkBeginCommandBuffer resets it).
    CommandPool(VkDevice device, std::uint32_t queueFamily,
                VkCommandPoolCreateFlags flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT);

    VkCommandPool get() const { return pool_.get(); }
    // A primary command buffer, freed with the pool (or by the caller).
    VkCommandBuffer allocate() const;

  private:
    VkDevice device_ = VK_NULL_HANDLE;
    UniqueCommandPool pool_;
};

// vkBeginCommandBuffer for one submission, vkEndCommandBuffer.
void beginRecording(VkCommandBuffer cmd);
void endRecording(VkCommandBuffer cmd);

class Fence {
  public:
    Fence() = default;  // empty, until one is moved in
    // signaled: the first wait() returns at once (a frame slot not used yet).
    explicit Fence(VkDevice device, bool signaled = false);

    VkFence get() const { return fence_.get(); }
    void wait() const;  // without a time limit
    void reset();       // before it is submitted again

  private:
    VkDevice device_ = VK_NULL_HANDLE;
    UniqueFence fence_;
};

UniqueSemaphore createSemaphore(VkDevice device);

}  // namespace rad
