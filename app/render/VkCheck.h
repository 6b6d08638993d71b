#pragma once
// Checking Vulkan results, and owning Vulkan handles.
//
// vkCheck is a plain function, not a macro: the call is evaluated exactly once
// where it is written, and the error names the call and the VkResult, e.g.
//   vkCheck(vkCreateFence(device, &info, nullptr, &fence), "vkCreateFence");
//   -> std::runtime_error("vkCreateFence failed: VK_ERROR_OUT_OF_HOST_MEMORY")

#include <vulkan/vulkan.h>

#include <string>
#include <utility>

namespace rad {

// "VK_ERROR_DEVICE_LOST" and the like; "VkResult(<n>)" for codes it does not know.
std::string vkResultName(VkResult result);

// Throws std::runtime_error("<call> failed: <result>") when result is an error code.
// Non-error success codes (VK_INCOMPLETE, VK_SUBOPTIMAL_KHR...) are returned to
// the caller, who knows whether they matter.
VkResult vkCheck(VkResult result, const char* call);

// A zeroed Vulkan struct with its sType set (brace-initialising only sType
// trips -Wmissing-field-initializers):
//   auto info = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
template <typename T>
T vkStruct(VkStructureType type) {
    T s{};
    s.sType = type;
    return s;
}

// Owns one handle created from a VkDevice and destroys it with Destroy
// (vkDestroyPipeline, vkFreeMemory, ...). Move-only. The device must outlive it.
template <typename T, auto Destroy>
class DeviceHandle {
  public:
    DeviceHandle() = default;
    DeviceHandle(VkDevice device, T handle) : device_(device), handle_(handle) {}
    ~DeviceHandle() { reset(); }

    DeviceHandle(const DeviceHandle&) = delete;
    DeviceHandle& operator=(const DeviceHandle&) = delete;
    DeviceHandle(DeviceHandle&& other) noexcept
        : device_(other.device_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
    DeviceHandle& operator=(DeviceHandle&& other) noexcept {
        if (this != &other) {
            reset();
            device_ = other.device_;
            handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
        }
        return *this;
    }

    T get() const { return handle_; }
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

    void reset() {
        if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }

  private:
    VkDevice device_ = VK_NULL_HANDLE;
    T handle_ = VK_NULL_HANDLE;
};

using UniqueBuffer = DeviceHandle<VkBuffer, &vkDestroyBuffer>;
using UniqueImage = DeviceHandle<VkImage, &vkDestroyImage>;
using UniqueImageView = DeviceHandle<VkImageView, &vkDestroyImageView>;
using UniqueMemory = DeviceHandle<VkDeviceMemory, &vkFreeMemory>;
using UniqueShaderModule = DeviceHandle<VkShaderModule, &vkDestroyShaderModule>;
using UniquePipelineLayout = DeviceHandle<VkPipelineLayout, &vkDestroyPipelineLayout>;
using UniquePipeline = DeviceHandle<VkPipeline, &vkDestroyPipeline>;
using UniqueRenderPass = DeviceHandle<VkRenderPass, &vkDestroyRenderPass>;
using UniqueFramebuffer = DeviceHandle<VkFramebuffer, &vkDestroyFramebuffer>;
using UniqueCommandPool = DeviceHandle<VkCommandPool, &vkDestroyCommandPool>;
using UniqueFence = DeviceHandle<VkFence, &vkDestroyFence>;
using UniqueSemaphore = DeviceHandle<VkSemaphore, &vkDestroySemaphore>;
using UniqueSwapchain = DeviceHandle<VkSwapchainKHR, &vkDestroySwapchainKHR>;
using UniqueSampler = DeviceHandle<VkSampler, &vkDestroySampler>;
using UniqueDescriptorSetLayout = DeviceHandle<VkDescriptorSetLayout, &vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = DeviceHandle<VkDescriptorPool, &vkDestroyDescriptorPool>;

}  // namespace rad
