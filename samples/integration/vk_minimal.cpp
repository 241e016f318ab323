// The smallest Vulkan integration: SAO recorded into your own command buffer. The block between
// the readme markers is quoted in README.md (a test keeps the two identical).
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sao/presets.h"
#include "sao/vulkan/effect.h"
#include "sao/vulkan/headless.h"

int main() {
  // Stand-in for your engine: a headless device and a depth image of a flat floor.
  std::unique_ptr<sao::vk::headless::Context> device;
  if (!sao::vk::headless::Context::create({}, device).ok()) return 1;
  const std::uint32_t width = 320, height = 180;
  sao::DepthImage floor{{width, height}, sao::DepthFormat::D32F, {}};
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x)
      floor.texels.push_back(sao::encodeDepth(sao::DepthFormat::D32F, 0.5 + 0.4 * y / height));
  sao::vk::headless::Image depth;
  if (!device->uploadDepth(floor, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth).ok()) return 1;
  const sao::vk::DeviceContext deviceContext = device->deviceContext();  // your instance, device, proc addrs

  // [readme-vulkan]
  sao::vk::Config config;
  config.camera = sao::perspectiveCamera(std::numbers::pi / 3, width, height, 0.1, INFINITY,
                                         sao::ClipDepth::ZeroToOne, /*reversedZ=*/true);
  config.settings = sao::presetSettings(sao::Preset::Medium);
  config.depthFormat = VK_FORMAT_D32_SFLOAT;
  std::unique_ptr<sao::vk::Effect> ao;
  sao::Status status = sao::vk::Effect::create(deviceContext, config, ao);
  sao::vk::Inputs inputs;
  inputs.depth = {depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, {width, height}};
  auto recordInto = [&](VkCommandBuffer cmd) { if (status) status = ao->record(cmd, inputs); };
  // ... recordInto(yourCommandBuffer), submit; the output is left in config.outputLayout:
  // sao::vk::OutputImage result = ao->output();
  // [/readme-vulkan]

  if (status) {
    if (sao::Status s = device->submit(recordInto); !s) status = s;
  }
  if (!status) std::fprintf(stderr, "sao: %s\n", status.message.c_str());
  std::printf("Vulkan: %s, output %ux%u\n", status ? "ok" : "failed", status ? ao->output().extent.width : 0,
              status ? ao->output().extent.height : 0);
  ao.reset();
  device->destroy(depth);
  return status ? 0 : 1;
}
