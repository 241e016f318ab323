// The engine's transfers between the host and its images: a host depth uploaded into an image of
// its own, and any colour image the effect uses (its output, an intermediate) read back as floats.
#pragma once
#include <cstdint>

#include "engine_device.h"
#include "engine_images.h"
#include "sao/image.h"
#include "sao_effect.h"

namespace sao::vkengine {

// `depth` (single-sampled D32F, or LinearZ as R32_SFLOAT) copied into a new sampled image, left in
// SHADER_READ_ONLY_OPTIMAL after a transfer write (a frame's CallerWrote barrier orders its reads
// after the copy). UnsupportedFormat for other depth or a device that cannot sample the format.
Status uploadDepth(const Device& device, const DepthImage& depth, Image& out);

// Level `level` of `image` (gen format `format`: 32-bit float, binary16 or 8-bit unorm components),
// which lives in GENERAL and was last written by compute shaders (or read back before), into
// `out` (the format's channels, row 0 first). The image goes through TRANSFER_SRC_OPTIMAL and is
// back in GENERAL for compute shaders when this returns.
Status readImage(const Device& device, const Image& image, gen::Format format, std::uint32_t level, FloatImage& out);

}  // namespace sao::vkengine
