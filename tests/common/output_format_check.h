// The output-format tests of every GPU backend (sao/output.h): a backend's output texels against
// the CPU reference's, channel by channel. Channels the mask selects agree to the reference tests'
// bounds (binary16 formats: 99.9% within 2/255, none beyond 4/255; 8-bit UNORM formats: the byte
// equal or one step off); channels it leaves out hold the sentinel texels bit for bit.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <cmath>

#include "image_compare.h"
#include "sao/output.h"

namespace sao::test {

// The stored byte of an 8-bit UNORM value read back as a float.
inline long unormByte(float v) { return std::lround(double(v) * 255.0); }

// Sentinel texels of an output before the effect runs: values each format holds exactly
// (multiples of 1/255 that are also binary16-exact are not needed: each format gets its own), so
// that untouched channels can be checked bit for bit after reading back.
inline FloatImage sentinelOutput(Extent e, gen::Format format) {
  const std::uint32_t channels = channelCount(format);
  FloatImage img(e, channels);
  const bool unorm = format == gen::Format::R8 || format == gen::Format::RGBA8;
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x)
      for (std::uint32_t c = 0; c < channels; ++c) {
        const std::uint32_t k = (x * 7 + y * 13 + c * 61) % 256;  // varies per texel and channel
        img.at(x, y, c) = unorm ? float(k) / 255.0f : float(k) / 256.0f;  // k/256: exact in binary16
      }
  return img;
}

struct OutputCheck {
  double maxAbs = 0;       // over selected channels (16F: |difference|; 8-bit: bytes / 255)
  long maxByteStep = 0;    // 8-bit formats: largest byte difference
  std::size_t keptDiffer = 0;  // texels of unselected channels not equal to the sentinel
};

// `actual` read back from the backend, `expected` the CPU reference's Result::ao (Float precision,
// same format, mask and sentinel), `sentinel` what the output held before.
template <typename Compare>
OutputCheck checkOutput(const FloatImage& actual, const FloatImage& expected, const FloatImage& sentinel,
                        gen::Format format, std::uint32_t mask, const Compare& compare, const std::string& name) {
  OutputCheck r;
  const std::uint32_t channels = channelCount(format);
  EXPECT_EQ(actual.channels, channels) << name;
  EXPECT_EQ(expected.channels, channels) << name;
  EXPECT_EQ(actual.extent, expected.extent) << name;
  if (actual.channels != channels || expected.channels != channels || actual.extent != expected.extent) return r;
  const bool unorm = format == gen::Format::R8 || format == gen::Format::RGBA8;
  float lowest = 1.0f;  // of the selected channels: the scene must show some obscurance
  for (std::size_t i = 0; i < actual.data.size(); ++i)
    if ((mask >> (i % channels)) & 1u) lowest = std::min(lowest, actual.data[i]);
  EXPECT_LT(lowest, 0.9f) << name << ": no obscurance in the selected channels, nothing compared";
  for (std::uint32_t c = 0; c < channels; ++c) {
    const bool selected = ((mask >> c) & 1u) != 0;
    if (!selected) {
      for (std::uint32_t y = 0; y < actual.extent.height; ++y)
        for (std::uint32_t x = 0; x < actual.extent.width; ++x) {
          const bool same = unorm ? unormByte(actual.at(x, y, c)) == unormByte(sentinel.at(x, y, c))
                                  : actual.at(x, y, c) == sentinel.at(x, y, c);
          if (!same) ++r.keptDiffer;
        }
      continue;
    }
    if (unorm) {
      for (std::size_t i = c; i < actual.data.size(); i += channels)
        r.maxByteStep = std::max(r.maxByteStep, std::labs(unormByte(actual.data[i]) - unormByte(expected.data[i])));
      r.maxAbs = std::max(r.maxAbs, double(r.maxByteStep) / 255.0);
    } else {
      const Agreement a = compare(actual, expected, c, 2.0 / 255.0, 4.0 / 255.0, name + "_c" + std::to_string(c));
      EXPECT_TRUE(acceptable(a)) << name << " channel " << c << ": max " << a.maxAbs * 255 << "/255, p99.9 "
                                 << a.p999 * 255 << "/255, " << a.beyond << " beyond 4/255";
      r.maxAbs = std::max(r.maxAbs, a.maxAbs);
    }
  }
  EXPECT_LE(r.maxByteStep, 1) << name << ": an 8-bit channel is more than one step off the CPU reference";
  EXPECT_EQ(r.keptDiffer, 0u) << name << ": channels outside the mask changed";
  std::printf("OUTPUT %-34s max %.3f/255%s, kept texels changed %zu\n", name.c_str(), r.maxAbs * 255,
              unorm ? (" (bytes: max step " + std::to_string(r.maxByteStep) + ")").c_str() : "", r.keptDiffer);
  return r;
}

// The format x mask cases every backend runs: each format with all its channels, the RGBA formats
// with masks that keep some channels, and the multiply blend (the apply step: the sentinel texels,
// all in [0, 1), times A, so the selected channels' differences stay within A's bounds).
struct OutputCase {
  gen::Format format;
  std::uint32_t mask;
  OutputBlend blend = OutputBlend::Replace;
};
inline constexpr OutputCase kOutputCases[] = {
    {gen::Format::R16F, kAllChannels},
    {gen::Format::R8, kAllChannels},
    {gen::Format::R8, kChannelR},
    {gen::Format::RGBA8, kAllChannels},
    {gen::Format::RGBA8, kChannelA},
    {gen::Format::RGBA8, kChannelR | kChannelB},
    {gen::Format::RGBA16F, kAllChannels},
    {gen::Format::RGBA16F, kChannelG},
    {gen::Format::RGBA16F, kChannelG | kChannelB | kChannelA},
    {gen::Format::R16F, kAllChannels, OutputBlend::Multiply},
    {gen::Format::R8, kAllChannels, OutputBlend::Multiply},
    {gen::Format::RGBA8, kChannelR | kChannelG | kChannelB, OutputBlend::Multiply},
    {gen::Format::RGBA16F, kChannelR | kChannelG | kChannelB, OutputBlend::Multiply},
};

inline std::string caseName(const OutputCase& c) {
  return std::string(formatName(c.format)) + "_mask" + std::to_string(c.mask) +
         (c.blend == OutputBlend::Multiply ? "_multiply" : "");
}

// An RGBA16F colour target as an engine's lit HDR buffer holds it, for the multiply blend: values
// from -8 to 55.75 in steps of 1/4 (exact in binary16), and in every 97th texel an infinity or a
// NaN in channel R, which the blend stores back unchanged.
inline FloatImage hdrColour(Extent e) {
  FloatImage img(e, 4);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x)
      for (std::uint32_t c = 0; c < 4; ++c) img.at(x, y, c) = float(int((x * 7 + y * 13 + c * 61) % 256) - 32) / 4.0f;
  for (std::size_t i = 0; i < img.data.size() / 4; i += 97)
    img.data[i * 4] = (i / 97) % 3 == 0 ? INFINITY : (i / 97) % 3 == 1 ? -INFINITY : NAN;
  return img;
}

// The multiply blend on the HDR colour: channel A kept bit for bit, non-finite R texels stored back
// as they were (NaN as a NaN), and elsewhere the product within the agreement bounds scaled by the
// texel's magnitude (A's own bounds, 2/255 for 99.9% and 4/255 for all, times |colour|) plus half a
// binary16 step of the product, against the CPU reference (Float). Returns the number of texels
// outside those bounds.
inline std::size_t checkHdrMultiply(const FloatImage& actual, const FloatImage& expected, const FloatImage& colour,
                                    const std::string& name) {
  std::size_t bad = 0, beyondP999 = 0, selected = 0, nonFinite = 0, changed = 0;
  double worst = 0;
  for (std::size_t i = 0; i < actual.data.size(); ++i) {
    const std::size_t c = i % 4;
    const float a = actual.data[i], e = expected.data[i], s = colour.data[i];
    if (c == 3 || !std::isfinite(s)) {
      const bool same = std::isnan(s) ? std::isnan(a) && std::isnan(e) : a == s && e == s;
      bad += !same;
      nonFinite += c != 3;
      continue;
    }
    ++selected;
    changed += a != s;
    const double step = std::ldexp(1.0, std::max(std::ilogb(std::max(std::fabs(e), 6.1e-5f)) - 10, -24));
    const double d = std::fabs(double(a) - double(e)) - 0.5 * step;
    const double scale = std::max(double(std::fabs(s)), 1e-30);
    worst = std::max(worst, d / scale);
    bad += d > 4.0 / 255.0 * scale;
    beyondP999 += d > 2.0 / 255.0 * scale;
  }
  EXPECT_GT(nonFinite, 0u) << name;
  EXPECT_GT(changed, selected / 10) << name << ": the multiply left nearly every texel as it was";
  EXPECT_LE(beyondP999, selected / 1000) << name;
  EXPECT_EQ(bad, 0u) << name;
  std::printf("HDR MULTIPLY %-24s worst |difference| / |colour| %.3f/255, %zu non-finite texels kept\n", name.c_str(),
              worst * 255, nonFinite);
  return bad;
}

}  // namespace sao::test
