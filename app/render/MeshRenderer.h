#pragma once
// Drawing a MeshSnapshot into any render pass with one colour and one depth
// attachment: the offscreen renderer's, or a swapchain's.
//
//   GpuMesh mesh(context, snapshot);                     // upload once per snapshot
//   GpuTextures textures(context, snapshot.textures);    // once per texture list (GpuTextures.h)
//   MeshRenderer renderer(context, renderPass);          // once per render pass
//   ... vkCmdBeginRenderPass(cmd, ...);
//   renderer.draw(cmd, mesh, textures, viewProjection, extent, options);  // surfaces, then lines
// viewProjection is in double and maps world coordinates: the draw moves it to
// the snapshot's origin (MeshSnapshot::origin) before it goes to the GPU in
// float, so a scene far from the world's origin keeps its detail.
//   ... vkCmdEndRenderPass(cmd);
//
// The textures are an argument of each draw, not state of the renderer: the
// descriptor set belongs to the GpuTextures (written once), so a frame in
// flight keeps reading the set it was recorded with while the next frame
// draws with a new one. Both objects must outlive the command buffer's
// execution. A textured vertex is drawn as colour * texel * texelScale, an
// untextured one (layer -1) as its colour.
//
// Exposure is a draw option (a push constant): changing it re-records, it
// does not re-upload.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <glm/glm.hpp>

#include "render/GpuResources.h"
#include "render/GpuTextures.h"
#include "render/RenderPass.h"
#include "render/VkCheck.h"

namespace rad {

class VulkanContext;
struct MeshSnapshot;

// Vertex layout shared by surfaces and lines (shaders/gouraud.vert). Lines
// use it too, untextured, so that one pair of shaders draws both.
struct MeshVertex {
    glm::vec3 position;
    glm::vec3 color;  // linear RGB
    glm::vec2 uv{0.0f};
    glm::vec3 texelScale{1.0f};
    // GpuTextures layer (MeshSnapshot::textureLayer) in the low 16 bits, the
    // texture's Texture::Wrap in u and v above them; -1: untextured.
    std::int32_t layer = -1;
};

inline constexpr int kWrapUShift = 16, kWrapVShift = 18;

// The GPU copy of one MeshSnapshot (its textures go to a GpuTextures). It
// must stay alive until the command buffers that draw it have finished
// executing.
class GpuMesh {
  public:
    // Throws std::runtime_error naming what does not fit: colours, uvs,
    // texture layers or texel scales not one per vertex (the last three may
    // all be empty), a layer outside -1..textures.size()-1, an index out of
    // range, an odd number of line points.
    GpuMesh(const VulkanContext& context, const MeshSnapshot& snapshot);

    std::uint32_t indexCount() const { return indexCount_; }
    std::uint32_t lineVertexCount() const { return lineVertexCount_; }
    VkBuffer vertexBuffer() const { return vertices_.buffer(); }
    VkBuffer indexBuffer() const { return indices_.buffer(); }
    VkBuffer lineBuffer() const { return lines_.buffer(); }
    const glm::dvec3& origin() const { return origin_; }  // MeshSnapshot::origin

  private:
    GpuBuffer vertices_;
    GpuBuffer indices_;
    GpuBuffer lines_;
    std::uint32_t indexCount_ = 0;
    std::uint32_t lineVertexCount_ = 0;
    glm::dvec3 origin_{0.0};
};

struct MeshDrawOptions {
    bool surfaces = true;
    bool overlays = true;    // the snapshot's line pairs, drawn over the surfaces
    float lineWidth = 1.0f;  // clamped to the device's range; 1 without wideLines
    // EV: surfaces are written as radiosity times 2^exposure. Overlay lines
    // are markers and keep their colours.
    double exposure = 0.0;
};

// The push constants of shaders/gouraud.vert and gouraud.frag, for both stages.
struct DrawPushConstants {
    glm::mat4 viewProjection;
    float exposureScale;  // 2^EV
};

class MeshRenderer {
  public:
    // renderPass: subpass 0 has one colour attachment and a depth attachment.
    // output: what that colour attachment expects (ShaderOutput::SrgbEncoded
    // for a UNORM swapchain).
    MeshRenderer(const VulkanContext& context, VkRenderPass renderPass,
                 ShaderOutput output = ShaderOutput::Linear);

    // Records into cmd, inside the render pass. Sets viewport and scissor to
    // the whole extent and binds textures' descriptor set. viewProjection
    // maps world to Vulkan clip space (the mesh's origin is folded in here). textures: built from the snapshot's
    // textures (a mesh without textured vertices may use any GpuTextures).
    void draw(VkCommandBuffer cmd, const GpuMesh& mesh, const GpuTextures& textures,
              const glm::dmat4& viewProjection, VkExtent2D extent,
              const MeshDrawOptions& options = {}) const;

  private:
    UniquePipeline createPipeline(VkDevice device, VkRenderPass renderPass, bool lines,
                                  ShaderOutput output) const;

    UniqueDescriptorSetLayout textureSetLayout_;  // set 0: createTextureSetLayout
    UniquePipelineLayout layout_;
    UniquePipeline surfacePipeline_;  // triangles, Gouraud, depth test and write, no culling
    UniquePipeline linePipeline_;     // line list, no depth test: always on top
    bool wideLines_ = false;
    float lineWidthRange_[2] = {1.0f, 1.0f};
};

}  // namespace rad
