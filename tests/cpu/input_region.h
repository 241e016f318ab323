// The depth input as a region of a larger texture (Inputs::offset on every backend): a region
// image placed at an offset inside a bigger one whose other texels hold junk that would change
// the result if any of them were read. Shared by the CPU, OpenGL and Vulkan region tests.
#pragma once
#include <cstdint>
#include <string>

#include "sao/image.h"
#include "sao/plan.h"

namespace sao::test {

// One placement: the camera's viewport and guard band inside a texture of `texture` at `offset`.
struct RegionCase {
  const char* name;
  std::uint32_t width, height, guard;
  Extent texture;
  Offset offset;
};

// The cases: the 1279x720 camera over a 1280x720 buffer (dynamic resolution at the
// origin), odd sizes at odd offsets with and without a guard band, and a region at the far corner.
inline constexpr RegionCase kRegionCases[] = {
    {"w1279h720_at0_0_in1280x720", 1279, 720, 0, {1280, 720}, {0, 0}},
    {"w641h359_g0_at3_5_in700x400", 641, 359, 0, {700, 400}, {3, 5}},
    {"w641h359_g3_at3_5_in700x400", 641, 359, 3, {700, 400}, {3, 5}},
    {"w97h61_g3_at_far_corner", 97, 61, 3, {120, 80}, {120 - 103, 80 - 67}},
};

// A texel hash in [0, 1): the junk differs from texel to texel, so a shifted read shows.
inline double junk(std::uint32_t x, std::uint32_t y) {
  std::uint32_t h = x * 0x9E3779B1u ^ (y + 0x7F4A7C15u) * 0x85EBCA77u;
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  return double(h >> 8) / double(1u << 24);
}

// `region` at `offset` inside a `texture`-sized image; every other texel is valid geometry at a
// varying depth (hardware depth in [0.2, 0.7), linear z in [-1.5, -0.5)), never sky.
inline DepthImage embedDepth(const DepthImage& region, Extent texture, Offset offset) {
  DepthImage out;
  out.extent = texture;
  out.format = region.format;
  out.texels.resize(std::size_t(texture.width) * texture.height);
  for (std::uint32_t y = 0; y < texture.height; ++y)
    for (std::uint32_t x = 0; x < texture.width; ++x) {
      const bool inside = x >= offset.x && y >= offset.y && x - offset.x < region.extent.width &&
                          y - offset.y < region.extent.height;
      const double d = region.format == DepthFormat::LinearZ ? -0.5 - junk(x, y) : 0.2 + 0.5 * junk(x, y);
      out.texels[std::size_t(y) * texture.width + x] =
          inside ? region.texels[std::size_t(y - offset.y) * region.extent.width + (x - offset.x)]
                 : encodeDepth(region.format, d);
    }
  return out;
}

// The same for normals: junk outside is a unit normal facing away from the region's.
inline FloatImage embedNormals(const FloatImage& region, Extent texture, Offset offset) {
  FloatImage out(texture, region.channels);
  for (std::uint32_t y = 0; y < texture.height; ++y)
    for (std::uint32_t x = 0; x < texture.width; ++x) {
      const bool inside = x >= offset.x && y >= offset.y && x - offset.x < region.extent.width &&
                          y - offset.y < region.extent.height;
      for (std::uint32_t c = 0; c < region.channels; ++c)
        out.at(x, y, c) = inside ? region.at(x - offset.x, y - offset.y, c) : (c == 0 ? float(junk(x, y)) - 1.0f : 0.0f);
    }
  return out;
}

inline std::string offsetText(Offset o) { return "(" + std::to_string(o.x) + ", " + std::to_string(o.y) + ")"; }

}  // namespace sao::test
