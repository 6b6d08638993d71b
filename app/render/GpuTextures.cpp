#include "render/GpuTextures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "image/Image.h"
#include "radiosity/Scene.h"
#include "render/VulkanContext.h"

namespace rad {
namespace {

constexpr VkFormat kTextureFormat = VK_FORMAT_R8G8B8A8_SRGB;

// The sRGB decoding of every 8-bit value: resampling averages light, not
// encoded values (a black and white checker shrinks to mid grey in linear
// terms, 0.5, not to the darker encoded 0.5).
std::array<float, 256> srgbDecodeTable() {
    std::array<float, 256> table{};
    for (int i = 0; i < 256; ++i) {
        const double c = i / 255.0;
        table[i] =
            static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return table;
}

// One source texel and its weight in a destination texel, along one axis.
struct Tap {
    std::uint32_t index;
    float weight;
};

// The taps of each destination texel along an axis of `from` texels resized
// to `to`: bilinear between texel centres at ceil(from / to) points spread
// over the texel's footprint (one point when enlarging), repeated at the
// edges as the sampler repeats.
std::vector<std::vector<Tap>> resampleTaps(std::uint32_t from, std::uint32_t to) {
    const double ratio = static_cast<double>(from) / to;
    const auto points = static_cast<std::uint32_t>(std::max(1.0, std::ceil(ratio)));
    const auto wrap = [from](long long i) {
        const long long n = from;
        return static_cast<std::uint32_t>(((i % n) + n) % n);
    };
    std::vector<std::vector<Tap>> taps(to);
    for (std::uint32_t d = 0; d < to; ++d)
        for (std::uint32_t k = 0; k < points; ++k) {
            const double s = (d + (k + 0.5) / points) * ratio - 0.5;  // in texel centres
            const double i0 = std::floor(s);
            const double f = s - i0;
            const auto i = static_cast<long long>(i0);
            taps[d].push_back({wrap(i), static_cast<float>((1.0 - f) / points)});
            taps[d].push_back({wrap(i + 1), static_cast<float>(f / points)});
        }
    return taps;
}

// Writes `texture` resized to width x height into `out` (sRGB RGBA8).
void resampleInto(const Texture& texture, std::uint32_t width, std::uint32_t height,
                  std::uint8_t* out) {
    if (texture.width == width && texture.height == height) {
        std::memcpy(out, texture.srgba.data(), texture.srgba.size());
        return;
    }
    static_assert(sizeof(float) == 4);
    const std::array<float, 256> decode = srgbDecodeTable();
    const std::vector<std::vector<Tap>> tapsX = resampleTaps(texture.width, width);
    const std::vector<std::vector<Tap>> tapsY = resampleTaps(texture.height, height);
    const std::uint8_t* src = texture.srgba.data();
    for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x = 0; x < width; ++x) {
            std::array<float, 4> sum{};  // linear RGB, alpha
            for (const Tap& ty : tapsY[y])
                for (const Tap& tx : tapsX[x]) {
                    const float w = ty.weight * tx.weight;
                    const std::uint8_t* t =
                        src + 4 * (std::size_t{ty.index} * texture.width + tx.index);
                    for (int c = 0; c < 3; ++c) sum[c] += w * decode[t[c]];
                    sum[3] += w * (t[3] / 255.0f);
                }
            std::uint8_t* o = out + 4 * (std::size_t{y} * width + x);
            for (int c = 0; c < 3; ++c) o[c] = encodeSrgb(sum[c]);
            o[3] = static_cast<std::uint8_t>(std::lround(std::clamp(sum[3], 0.0f, 1.0f) * 255.0f));
        }
}


}  // namespace

UniqueDescriptorSetLayout createTextureSetLayout(VkDevice device) {
    VkDescriptorSetLayoutBinding binding{};
    binding.binding = 0;
    binding.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    binding.descriptorCount = 1;
    binding.stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
    auto info = vkStruct<VkDescriptorSetLayoutCreateInfo>(
        VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    info.bindingCount = 1;
    info.pBindings = &binding;
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    vkCheck(vkCreateDescriptorSetLayout(device, &info, nullptr, &layout),
            "vkCreateDescriptorSetLayout");
    return {device, layout};
}

TextureLayers packTextureLayers(const std::vector<std::shared_ptr<const Texture>>& textures,
                                std::uint32_t maxSide) {
    TextureLayers packed;
    if (textures.empty()) {
        packed.srgba = {255, 255, 255, 255};
        return packed;
    }
    packed.width = packed.height = 0;
    for (std::size_t i = 0; i < textures.size(); ++i) {
        const Texture* t = textures[i].get();
        const std::string what = "texture " + std::to_string(i) +
                                 (t && !t->name.empty() ? " '" + t->name + "'" : std::string());
        if (!t) throw std::runtime_error("MeshSnapshot: " + what + " is null");
        if (t->width == 0 || t->height == 0)
            throw std::runtime_error("MeshSnapshot: " + what + " has no texels (" +
                                     std::to_string(t->width) + "x" + std::to_string(t->height) +
                                     ")");
        if (t->srgba.size() != std::size_t{t->width} * t->height * 4)
            throw std::runtime_error(
                "MeshSnapshot: " + what + " has " + std::to_string(t->srgba.size()) +
                " bytes, not " + std::to_string(t->width) + "x" + std::to_string(t->height) + "x4");
        packed.width = std::max(packed.width, t->width);
        packed.height = std::max(packed.height, t->height);
    }
    packed.width = std::min(packed.width, maxSide);
    packed.height = std::min(packed.height, maxSide);
    packed.layers = static_cast<std::uint32_t>(textures.size());
    const std::size_t layerBytes = std::size_t{packed.width} * packed.height * 4;
    packed.srgba.resize(layerBytes * packed.layers);
    for (std::size_t i = 0; i < textures.size(); ++i)
        resampleInto(*textures[i], packed.width, packed.height,
                     packed.srgba.data() + i * layerBytes);
    return packed;
}

GpuTextures::GpuTextures(const VulkanContext& context,
                         const std::vector<std::shared_ptr<const Texture>>& textures)
    : sources_(textures) {
    const std::uint32_t maxLayers = context.properties().limits.maxImageArrayLayers;
    if (textures.size() > maxLayers)
        throw std::runtime_error("MeshSnapshot: " + std::to_string(textures.size()) +
                                 " textures, more than the Vulkan device's " +
                                 std::to_string(maxLayers) + " image array layers");
    const std::uint32_t maxSide =
        std::min(kMaxSide, context.properties().limits.maxImageDimension2D);
    const TextureLayers packed = packTextureLayers(textures, maxSide);
    extent_ = {packed.width, packed.height};
    layers_ = packed.layers;
    VkDevice device = context.device();

    // The image: one array layer per texture, sampled in the fragment shader.
    image_ = GpuImage(context, extent_.width, extent_.height, kTextureFormat,
                      VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_COLOR_BIT, layers_);
    const VkImage image = image_.image();

    // Upload: staging buffer -> image, then ready for the fragment shader.
    GpuBuffer staging(context, packed.srgba.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    staging.write(packed.srgba.data(), packed.srgba.size());
    context.runOneShot([&](VkCommandBuffer cmd) {
        auto toCopy = colorLayoutBarrier(image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, layers_);
        toCopy.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             0, 0, nullptr, 0, nullptr, 1, &toCopy);
        // Layers follow each other in the buffer, tightly packed: one region.
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, layers_};
        region.imageExtent = {extent_.width, extent_.height, 1};
        vkCmdCopyBufferToImage(cmd, staging.buffer(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               1, &region);
        auto toRead = colorLayoutBarrier(image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, layers_);
        toRead.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        toRead.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                             &toRead);
    });  // waits: the staging buffer may go

    auto samplerInfo = vkStruct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
    samplerInfo.magFilter = VK_FILTER_LINEAR;
    samplerInfo.minFilter = VK_FILTER_LINEAR;
    samplerInfo.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    samplerInfo.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    samplerInfo.addressModeV = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    samplerInfo.maxLod = 0.0f;
    VkSampler sampler = VK_NULL_HANDLE;
    vkCheck(vkCreateSampler(device, &samplerInfo, nullptr, &sampler), "vkCreateSampler");
    sampler_ = UniqueSampler(device, sampler);

    // The descriptor set, written once: see the header.
    setLayout_ = createTextureSetLayout(device);
    const VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
    auto poolInfo =
        vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &poolSize;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    vkCheck(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
    pool_ = UniqueDescriptorPool(device, pool);
    auto allocInfo =
        vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    allocInfo.descriptorPool = pool;
    allocInfo.descriptorSetCount = 1;
    const VkDescriptorSetLayout setLayout = setLayout_.get();
    allocInfo.pSetLayouts = &setLayout;
    vkCheck(vkAllocateDescriptorSets(device, &allocInfo, &set_), "vkAllocateDescriptorSets");

    const VkDescriptorImageInfo imageDescriptor{sampler, image_.view(),
                                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    auto write = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    write.dstSet = set_;
    write.dstBinding = 0;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    write.pImageInfo = &imageDescriptor;
    vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
}

}  // namespace rad
