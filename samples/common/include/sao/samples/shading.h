// A simple environment light for looking at AO: a sky/ground hemisphere light on a grey albedo.
#pragma once
#include "sao/image.h"

namespace sao::samples {

// 3-channel linear images: environment light (from camera-space normals and the camera's up,
// y) times `ao` if given. Sky pixels (normal w = 0 in `normals`' 4th channel unused; position w = 0)
// get the sky colour.
FloatImage shadeEnvironment(const FloatImage& normals, const FloatImage& positions, const FloatImage* ao,
                            std::uint32_t guardBand);

// Linear -> sRGB 8-bit PNG, row height-1 first (the top of the screen).
Status writeRgbPng(const std::string& path, const FloatImage& rgb);

// Unit vectors (3 channels, e.g. camera-space bent normals) as an 8-bit normal map: 0.5 + 0.5 v per
// channel, no sRGB curve (as the effect's rgba8 output stores a bent normal), row height-1 first.
Status writeNormalPng(const std::string& path, const FloatImage& normals);

}  // namespace sao::samples
