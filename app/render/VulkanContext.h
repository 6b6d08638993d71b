#pragma once
// The Vulkan objects every renderer needs: instance, (optional) validation
// messenger, physical device, logical device with one graphics queue, and a
// command pool for one-shot work. Nothing here knows about windows: a viewer
// passes the surface/swapchain extensions and a presentation test through
// VulkanContextOptions and creates its surface in onInstanceCreated.

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "render/Commands.h"
#include "render/VkCheck.h"

namespace rad {

struct VulkanContextOptions {
    // Turn on VK_LAYER_KHRONOS_validation and a messenger that prints and counts
    // every warning and error. The environment variable RADIOSITY_VALIDATION=1
    // turns it on as well. Construction throws when the layer is not installed.
    bool validation = false;

    std::string applicationName = "radiosity";
    // Added to the instance (e.g. glfwGetRequiredInstanceExtensions) and device
    // (e.g. VK_KHR_swapchain) extension lists. Construction throws if one is missing.
    std::vector<std::string> instanceExtensions;
    std::vector<std::string> deviceExtensions;

    // Called once the instance exists, before the physical device is chosen:
    // the place to create a window surface (which its owner destroys before
    // the context).
    std::function<void(VkInstance)> onInstanceCreated;
    // Extra condition on the graphics queue family, e.g. presentation support
    // for the surface. Devices without a family passing it are skipped.
    std::function<bool(VkInstance, VkPhysicalDevice, std::uint32_t family)> queueFamilyFilter;

    // Prefer a CPU implementation (lavapipe) when several devices qualify, so
    // that images compared against references come from the same rasteriser.
    bool preferSoftwareDevice = true;
};

class VulkanContext {
  public:
    explicit VulkanContext(VulkanContextOptions options = {});
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    std::uint32_t queueFamily() const { return queueFamily_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    // The features actually enabled on the device (wideLines and
    // fillModeNonSolid when the device has them).
    const VkPhysicalDeviceFeatures& enabledFeatures() const { return enabledFeatures_; }
    std::string deviceName() const { return properties_.deviceName; }

    bool validationEnabled() const { return messenger_ != VK_NULL_HANDLE; }
    // Warnings and errors reported by the validation layer so far (0 when it is off).
    std::size_t validationMessageCount() const { return counter_->load(); }
    // The same count, readable after the context is gone: destroying the
    // device and instance is when leaked objects are reported.
    std::shared_ptr<const std::atomic<std::size_t>> validationMessageCounter() const {
        return counter_;
    }

    // A memory type index allowed by typeBits with all of the required flags.
    // Throws when there is none.
    std::uint32_t findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required) const;

    // vkQueueSubmit under a lock: the one queue is shared by every thread.
    void submit(const VkSubmitInfo& info, VkFence fence) const;
    // The same for one command buffer without semaphores.
    void submit(VkCommandBuffer cmd, VkFence fence) const;
    // Records with record(), submits and waits. For uploads and other rare work.
    void runOneShot(const std::function<void(VkCommandBuffer)>& record) const;

    // Held while using the queue directly (vkQueuePresentKHR, ImGui uploads).
    std::mutex& queueMutex() const { return queueMutex_; }

  private:
    void createInstance(const VulkanContextOptions& options, bool validation);
    void pickPhysicalDevice(const VulkanContextOptions& options);
    void createDevice(const VulkanContextOptions& options);
    void destroy();  // releases whatever exists, in reverse order of creation

    // Outlives the instance: messages sent while the instance is destroyed
    // still land somewhere valid.
    std::shared_ptr<std::atomic<std::size_t>> counter_ =
        std::make_shared<std::atomic<std::size_t>>(0);
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    VkPhysicalDeviceFeatures enabledFeatures_{};
    std::uint32_t queueFamily_ = 0;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    CommandPool commandPool_;  // for runOneShot, under poolMutex_
    mutable std::mutex queueMutex_;
    mutable std::mutex poolMutex_;
};

// True when RADIOSITY_VALIDATION is set to 1 in the environment.
bool validationRequestedByEnvironment();

}  // namespace rad
