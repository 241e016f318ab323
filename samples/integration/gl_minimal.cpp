// The smallest OpenGL integration: SAO on a depth texture in your own GL 4.3+ context. The block
// between the readme markers is quoted in README.md (a test keeps the two identical).
#include <cstdio>
#include <numbers>

#include "sao/gl/effect.h"
#include "sao/presets.h"
#include "sao/gl/headless.h"
#include "sao/gl/texture_io.h"

int main() {
  // Stand-in for your engine: a headless context and a depth texture of a flat floor.
  std::unique_ptr<sao::gl::HeadlessContext> context;
  if (!sao::gl::HeadlessContext::create(context).ok()) return 1;
  const std::uint32_t width = 320, height = 180;
  sao::DepthImage floor{{width, height}, sao::DepthFormat::D32F, {}};
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x)
      floor.texels.push_back(sao::encodeDepth(sao::DepthFormat::D32F, 0.5 + 0.4 * y / height));
  std::uint32_t depthTexture = 0;
  if (!sao::gl::uploadDepth(floor, sao::gl::GlDepth::D32F, depthTexture).ok()) return 1;

  // [readme-gl]
  std::unique_ptr<sao::gl::Effect> ao;
  sao::Status status = sao::gl::Effect::create(sao::gl::HeadlessContext::getProcAddress(), ao);
  sao::Camera camera = sao::perspectiveCamera(std::numbers::pi / 3, width, height, 0.1, 100.0,
                                              sao::ClipDepth::NegativeOneToOne, /*reversedZ=*/false);
  sao::Settings settings = sao::presetSettings(sao::Preset::Medium);
  settings.radius = 0.5f;  // metres
  sao::gl::Inputs inputs;
  inputs.depth = {depthTexture, sao::gl::kDepthComponent32F};
  if (status) status = ao->render(camera, settings, inputs);
  if (!status) std::fprintf(stderr, "sao: %s\n", status.message.c_str());
  const std::uint32_t aoTexture = ao ? ao->aoTexture() : 0;  // R16F, linear visibility in [0, 1]
  // [/readme-gl]

  std::printf("GL: %s, AO texture %u, %.1f MB planned\n", status ? "ok" : "failed", aoTexture,
              ao ? ao->plan().totalBytes / 1e6 : 0.0);
  ao.reset();
  sao::gl::deleteTexture(depthTexture);
  return status ? 0 : 1;
}
