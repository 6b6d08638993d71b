#pragma once
// Renders MeshSnapshots into a float image in memory, without a window.
//
//   VulkanContext context;
//   OffscreenRenderer renderer(context);
//   Image image = renderer.render(snapshot, view.viewProjection(), 512, 512);
//
// Attachments (R32G32B32A32_SFLOAT colour, D32 depth) and the readback buffer
// are kept between frames and only recreated when the size changes; so are
// the snapshot's textures, uploaded again only when its texture list is
// another (GpuTextures::sameSources).

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>

#include "image/Image.h"
#include "render/Commands.h"
#include "render/GpuResources.h"
#include "render/GpuTextures.h"
#include "render/ImageReadback.h"
#include "render/MeshRenderer.h"
#include "render/RenderPass.h"
#include "render/VkCheck.h"

namespace rad {

class VulkanContext;
struct MeshSnapshot;

class OffscreenRenderer {
  public:
    static constexpr VkFormat kColorFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

    // The context must outlive the renderer. Uses the context's queue; one
    // renderer must not be used by two threads at once. output:
    // ShaderOutput::SrgbEncoded renders what a UNORM window would show.
    explicit OffscreenRenderer(const VulkanContext& context, ShaderOutput output = ShaderOutput::Linear);

    // Linear RGB (times 2^options.exposure), top row first, background 0.
    // width and height >= 1, at most the device's maxImageDimension2D.
    Image render(const MeshSnapshot& snapshot, const glm::dmat4& viewProjection, int width,
                 int height, const MeshDrawOptions& options = {});
    // What the caller has uploaded already (the viewer's screenshot of the
    // mesh on screen).
    Image render(const GpuMesh& mesh, const GpuTextures& textures, const glm::dmat4& viewProjection,
                 int width, int height, const MeshDrawOptions& options = {});

    VkRenderPass renderPass() const { return renderPass_.get(); }

  private:
    // The attachments and readback buffer of one image size.
    struct Target {
        Target(const VulkanContext& context, VkRenderPass renderPass, VkExtent2D extent);
        VkExtent2D extent;
        GpuImage color;
        GpuImage depth;
        UniqueFramebuffer framebuffer;
        ImageReadback readback;
    };

    const VulkanContext& context_;
    UniqueRenderPass renderPass_;
    std::optional<MeshRenderer> meshRenderer_;
    CommandPool commandPool_;  // own pool: recording is not tied to the context's pool
    VkCommandBuffer commandBuffer_ = VK_NULL_HANDLE;  // freed with the pool
    Fence frameDone_;
    std::optional<Target> target_;
    // The last snapshot's textures (render(MeshSnapshot)); idle between calls,
    // each of which waits for its frame.
    std::optional<GpuTextures> textures_;
};

}  // namespace rad
