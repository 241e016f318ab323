// Multisampled test depth (Camera::depthSamplePolicy, DEPTH_MULTISAMPLE), shared by the CPU,
// OpenGL and Vulkan tests: a depth buffer of n samples per texel whose sample s of texel (x, y)
// comes from one of several single-sample layers (scenes rendered with the same camera), picked by a
// fixed hash, so that silhouettes, sky and nearer geometry mix inside texels as they do in MSAA.
// The GPU tests write exactly these values per sample (a fragment shader with per-sample shading
// writing gl_FragDepth) and compare the effect with the CPU reference run on this image.
#pragma once
#include <cstdint>
#include <vector>

#include "sao/image.h"

namespace sao::test {

// Which of `count` layers sample s of texel (x, y) takes (a fixed integer hash).
inline std::uint32_t msaaLayerOf(std::uint32_t x, std::uint32_t y, std::uint32_t s, std::uint32_t count) {
  std::uint32_t h = x * 73856093u ^ y * 19349663u ^ (s + 1u) * 83492791u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return h % count;
}

// `samples` samples per texel from `layers` (same extent and format, at least one).
inline DepthImage interleaveSamples(const std::vector<const DepthImage*>& layers, std::uint32_t samples) {
  DepthImage out;
  out.extent = layers.front()->extent;
  out.format = layers.front()->format;
  out.samples = samples;
  out.texels.resize(std::size_t(out.extent.width) * out.extent.height * samples);
  for (std::uint32_t y = 0; y < out.extent.height; ++y)
    for (std::uint32_t x = 0; x < out.extent.width; ++x)
      for (std::uint32_t s = 0; s < samples; ++s)
        out.texels[(std::size_t(y) * out.extent.width + x) * samples + s] =
            layers[msaaLayerOf(x, y, s, std::uint32_t(layers.size()))]->raw(x, y);
  return out;
}

// Sample s of every texel as a single-sample image.
inline DepthImage sampleImage(const DepthImage& msaa, std::uint32_t s) {
  DepthImage out;
  out.extent = msaa.extent;
  out.format = msaa.format;
  out.texels.resize(std::size_t(msaa.extent.width) * msaa.extent.height);
  for (std::uint32_t y = 0; y < msaa.extent.height; ++y)
    for (std::uint32_t x = 0; x < msaa.extent.width; ++x)
      out.texels[std::size_t(y) * msaa.extent.width + x] = msaa.raw(x, y, s);
  return out;
}

// The samples' values as floats, texel by texel (the layout of DepthImage::texels): what a GPU
// test's fragment shader writes to gl_FragDepth (D32F; exact, every value lies in [0, 1]).
inline std::vector<float> sampleValues(const DepthImage& msaa) {
  std::vector<float> out(msaa.texels.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = float(decodeDepth(msaa.format, msaa.texels[i]));
  return out;
}

}  // namespace sao::test
