#pragma once
// The textures of a MeshSnapshot on the GPU, for MeshRenderer::draw.
//
//   GpuTextures textures(context, snapshot.textures);   // upload once per texture list
//   if (!textures.sameSources(next.textures)) ...       // a new list: build another
//   renderer.draw(cmd, mesh, textures, viewProjection, extent);
//
// All textures go into one 2D array image (VK_FORMAT_R8G8B8A8_SRGB: sampling
// returns linear values), layer i = textures[i], so the shader picks a
// texture by a per-vertex layer index without descriptor indexing (lavapipe
// has none). An array needs one size for all layers: each texture is
// resampled on the CPU to the largest width and the largest height among
// them, at most kMaxSide. One sampler: bilinear, REPEAT in u and v, no
// mipmaps. The texture's own wrap modes (Texture::wrapU/wrapV) are not
// followed: every layer repeats. With no textures the image is one white
// texel, so the descriptor is always valid.
//
// The object owns its descriptor set (written once, at construction): a new
// texture list is a new GpuTextures, never a rewrite of a set that frames in
// flight may still read. Like GpuMesh it must stay alive until the command
// buffers that draw with it have finished. Move-only; the VulkanContext must
// outlive it.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "render/GpuResources.h"
#include "render/VkCheck.h"

namespace rad {

class VulkanContext;
struct Texture;

// The set layout of the textures: binding 0, one combined image sampler
// (sampler2DArray), fragment stage. MeshRenderer's pipeline layout and every
// GpuTextures' set are made from layouts created here: identically defined,
// hence compatible.
UniqueDescriptorSetLayout createTextureSetLayout(VkDevice device);

// The layers' pixels as uploaded: sRGB RGBA8, layer after layer, rows from
// the top. Exposed for tests; GpuTextures builds one.
struct TextureLayers {
    std::uint32_t width = 1, height = 1, layers = 1;
    std::vector<std::uint8_t> srgba;  // width * height * 4 * layers
};
// Every texture resampled to the common size (bilinear in linear RGB,
// repeated at the edges, averaged over the footprint when it shrinks);
// a texture already of that size is copied as it is. No textures: one white
// texel. Throws std::runtime_error naming the texture when one is null, empty
// or its srgba is not width * height * 4 bytes.
TextureLayers packTextureLayers(const std::vector<std::shared_ptr<const Texture>>& textures,
                                std::uint32_t maxSide);

class GpuTextures {
  public:
    static constexpr std::uint32_t kMaxSide = 2048;

    // Uploads through a staging buffer and waits (VulkanContext::runOneShot).
    // Throws std::runtime_error on a malformed texture (packTextureLayers) or
    // more textures than the device's maxImageArrayLayers.
    GpuTextures(const VulkanContext& context,
                const std::vector<std::shared_ptr<const Texture>>& textures);

    // True when `textures` is the list this was built from, pointer for
    // pointer: the upload can be reused.
    bool sameSources(const std::vector<std::shared_ptr<const Texture>>& textures) const {
        return sources_ == textures;
    }
    const std::vector<std::shared_ptr<const Texture>>& sources() const { return sources_; }

    VkDescriptorSet descriptorSet() const { return set_; }
    VkExtent2D layerExtent() const { return extent_; }
    std::uint32_t layerCount() const { return layers_; }

  private:
    std::vector<std::shared_ptr<const Texture>> sources_;
    GpuImage image_;  // one layer per texture, viewed as a 2D array
    UniqueSampler sampler_;
    UniqueDescriptorSetLayout setLayout_;
    UniqueDescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;  // freed with the pool
    VkExtent2D extent_{1, 1};
    std::uint32_t layers_ = 1;
};

}  // namespace rad
