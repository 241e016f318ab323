// A multisampled D32_SFLOAT depth image holding exactly the values of a multisampled DepthImage
// (tests/cpu/msaa_depth.h), for the Vulkan tests of DEPTH_MULTISAMPLE. The values cannot be copied
// into a multisampled image (vkCmdCopyBufferToImage needs one sample), so they are rendered: a
// full-screen triangle per sample, depth test ALWAYS with writes, gl_FragDepth read from a storage
// buffer and gl_SampleMask selecting the sample.
#pragma once
#include "sao/image.h"
#include "sao/status.h"
#include "sao/vulkan/headless.h"

namespace sao::vktest {

// `depth` is D32F with 2, 4, .. samples (one VkSampleCountFlagBits the device can render and
// sample for D32_SFLOAT). `out` is a D32_SFLOAT image of depth.samples samples (usage
// DEPTH_STENCIL_ATTACHMENT | SAMPLED) with a 2D view of its depth aspect, left in `layout`
// (DEPTH_STENCIL_READ_ONLY_OPTIMAL or SHADER_READ_ONLY_OPTIMAL) with the writes visible to
// compute-shader reads; free it with ctx.destroy(out).
Status writeMultisampledDepth(vk::headless::Context& ctx, const DepthImage& depth, VkImageLayout layout,
                              vk::headless::Image& out);

}  // namespace sao::vktest
