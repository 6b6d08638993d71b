#pragma once
// The render pass both renderers draw with, and what goes with it: one colour
// attachment and one depth attachment, both cleared, in one subpass
// (MeshRenderer's pipelines and ImGui's are made for it).
//
//   UniqueRenderPass pass = createColorDepthRenderPass(device, colorFormat, kDepthFormat,
//                                                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
//   UniqueFramebuffer fb = createFramebuffer(device, pass.get(), colorView, depthView, extent);
//   beginColorDepthPass(cmd, pass.get(), fb.get(), extent, {0, 0, 0, 0});
//   ... draw ...
//   vkCmdEndRenderPass(cmd);

#include <vulkan/vulkan.h>

#include <array>

#include "render/VkCheck.h"

namespace rad {

// What a colour attachment expects the fragment shader to write: linear
// values (float formats, and *_SRGB formats whose hardware encodes on store),
// or values already sRGB-encoded (8-bit UNORM formats, shown as written).
enum class ShaderOutput { Linear, SrgbEncoded };

// 32-bit float depth: lavapipe and every desktop GPU support it as an attachment.
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

// colorFinalLayout: where the colour image goes after the pass
// (TRANSFER_SRC_OPTIMAL to read it back, PRESENT_SRC_KHR to show it).
// The pass waits for earlier work on reused attachments (a previous frame's
// depth tests and colour readback, a swapchain acquire waited at colour
// output), and makes its colour writes visible to a transfer that follows.
UniqueRenderPass createColorDepthRenderPass(VkDevice device, VkFormat colorFormat, VkFormat depthFormat,
                                            VkImageLayout colorFinalLayout);

UniqueFramebuffer createFramebuffer(VkDevice device, VkRenderPass renderPass, VkImageView color,
                                    VkImageView depth, VkExtent2D extent);

// Begins the pass over the whole extent: colour cleared to clearColor, depth to 1.
void beginColorDepthPass(VkCommandBuffer cmd, VkRenderPass renderPass, VkFramebuffer framebuffer,
                         VkExtent2D extent, const std::array<float, 4>& clearColor);

}  // namespace rad
