#pragma once
// Presenting to a window surface: swapchain, one render pass (colour + depth),
// per-frame command buffers and synchronisation. Knows nothing about GLFW or
// ImGui: the caller records into the command buffer beginFrame() returns
// (MeshRenderer, then ImGui) and hands it back to endFrame().
//
//   WindowRenderer window(context, surface, [&] { return framebufferSize(); });
//   if (VkCommandBuffer cmd = window.beginFrame(clear)) {
//       meshRenderer.draw(cmd, mesh, viewProj, window.extent());
//       window.endFrame(keepMeshAlive);
//   }
//
// The swapchain is recreated when the window size changes or presentation
// reports it out of date. If the surface offers a *_SRGB format it is chosen,
// so linear values written by the shaders are encoded by the hardware;
// otherwise shaders encode (shaderOutput()).

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "render/Commands.h"
#include "render/GpuResources.h"
#include "render/RenderPass.h"
#include "render/VkCheck.h"

namespace rad {

class VulkanContext;

class WindowRenderer {
  public:
    static constexpr std::uint32_t kFramesInFlight = 2;

    // The surface and context must outlive the renderer. framebufferSize gives
    // the window's size in pixels (0 x 0 while minimised).
    WindowRenderer(const VulkanContext& context, VkSurfaceKHR surface,
                   std::function<VkExtent2D()> framebufferSize);
    ~WindowRenderer();
    WindowRenderer(const WindowRenderer&) = delete;
    WindowRenderer& operator=(const WindowRenderer&) = delete;

    VkRenderPass renderPass() const { return renderPass_.get(); }
    VkFormat colorFormat() const { return format_.format; }
    bool srgb() const;  // the hardware encodes linear output to sRGB
    // What shaders drawing here must write: linear, unless the swapchain is UNORM.
    ShaderOutput shaderOutput() const { return srgb() ? ShaderOutput::Linear : ShaderOutput::SrgbEncoded; }
    VkExtent2D extent() const { return extent_; }
    std::uint32_t minImageCount() const { return minImageCount_; }
    std::uint32_t imageCount() const { return static_cast<std::uint32_t>(images_.size()); }
    // Bumped whenever the swapchain is recreated (ImGui wants the image count).
    std::uint64_t swapchainGeneration() const { return generation_; }

    // Waits for the frame slot, acquires an image and begins the render pass
    // (cleared to clearColor, depth 1). VK_NULL_HANDLE: skip this frame
    // (minimised, or the swapchain was just recreated).
    VkCommandBuffer beginFrame(const std::array<float, 4>& clearColor);
    // Ends the render pass, submits and presents. keepAlive is held until the
    // GPU has finished the frame (the meshes it draws). With capturePath the
    // presented image is also written as an 8-bit PNG (waits for the frame).
    // Returns the frame's serial number (1, 2, ...).
    std::uint64_t endFrame(std::shared_ptr<const void> keepAlive, const std::string& capturePath = {});
    // Frames up to this serial number are known to be finished on the GPU
    // (learnt when beginFrame waits for a frame slot).
    std::uint64_t finishedFrames() const { return finished_; }

    // vkDeviceWaitIdle under the queue lock.
    void waitIdle() const;

  private:
    // One frame in flight: its commands, the fence that says they are done,
    // and what they draw, kept alive until then.
    struct Frame {
        VkCommandBuffer cmd = VK_NULL_HANDLE;  // freed with the pool
        Fence done;
        UniqueSemaphore imageAvailable;
        std::shared_ptr<const void> keepAlive;
        std::uint64_t serial = 0;
    };

    void createSwapchain();
    void destroySwapchain();
    void writeCapture(const std::string& path, const void* pixels) const;

    const VulkanContext& context_;
    VkSurfaceKHR surface_;
    std::function<VkExtent2D()> framebufferSize_;
    VkSurfaceFormatKHR format_{};
    UniqueRenderPass renderPass_;
    CommandPool commandPool_;
    std::array<Frame, kFramesInFlight> frames_;
    std::uint32_t frameIndex_ = 0;
    std::uint64_t submitted_ = 0, finished_ = 0;

    UniqueSwapchain swapchain_;
    VkExtent2D extent_{0, 0};
    std::uint32_t minImageCount_ = 2;
    std::uint64_t generation_ = 0;
    std::vector<VkImage> images_;  // owned by the swapchain
    std::vector<UniqueImageView> views_;
    std::vector<UniqueFramebuffer> framebuffers_;
    std::vector<UniqueSemaphore> renderFinished_;  // one per swapchain image
    std::vector<VkFence> imageFences_;             // the frame fence last using each image
    GpuImage depth_;
    bool captureSupported_ = false;
    std::uint32_t currentImage_ = 0;
    bool needsRecreate_ = false;
};

}  // namespace rad
