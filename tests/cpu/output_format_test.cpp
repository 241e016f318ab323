// The output as the engine wants it (sao/output.h) on the CPU reference: R8 rounding to the
// nearest 1/255 exactly as sao_round_to_unorm8 defines it, every format's selected channels
// holding A as that format rounds it (Float) or unrounded (Double), unselected channels keeping
// the initial output, the multiply blend (the apply step) exactly as sao_output_multiply defines it,
// and bad formats, masks, blends and initial outputs refused.
#include <cmath>
#include <string>

#include "untuned_settings.h"
#include "sao/presets.h"
#include "test_support.h"

namespace sao::test {
namespace {

using cpu::Precision;

TEST(OutputFormat, Unorm8RoundsToTheNearestStepHalvesUp) {
  const auto roundToUnorm8 = cpu::roundToUnorm8AsShader;
  EXPECT_EQ(roundToUnorm8(0.0f), 0.0f);
  EXPECT_EQ(roundToUnorm8(1.0f), 1.0f);
  EXPECT_EQ(roundToUnorm8(-0.25f), 0.0f) << "clamped";
  EXPECT_EQ(roundToUnorm8(1.5f), 1.0f) << "clamped";
  // floor(x * 255 + 0.5) in binary32: 0.51 of a step up rounds up, 0.49 rounds down.
  EXPECT_EQ(roundToUnorm8(0.51f / 255.0f), 1.0f / 255.0f);
  EXPECT_EQ(roundToUnorm8(0.49f / 255.0f), 0.0f);
  EXPECT_EQ(roundToUnorm8(0.5f), 128.0f / 255.0f) << "127.5 steps: halves go up";
  for (int k = 0; k <= 255; ++k) {
    const float step = float(k) / 255.0f;
    EXPECT_EQ(std::lround(roundToUnorm8(step) * 255.0), k) << "a step is its own value";
    EXPECT_EQ(std::lround(roundToUnorm8(step + 0.4f / 255.0f) * 255.0), std::min(k, 255)) << k;
  }
}

TEST(OutputFormat, MultiplyRoundsTheProductOnceAsTheFormatHoldsIt) {
  const auto multiply = cpu::outputMultiplyAsShader;
  // binary16: exact products stay, others go to the nearest binary16 (ties away from zero), of
  // either sign and beyond 1 (an HDR colour is not clamped).
  EXPECT_EQ(multiply(40.0f, 0.5f, false), 20.0f);
  EXPECT_EQ(multiply(-6.0f, 0.25f, false), -1.5f);
  EXPECT_EQ(multiply(65504.0f, 1.0f, false), 65504.0f) << "the largest binary16 stays";
  EXPECT_EQ(multiply(3.0f, 1.0f / 3.0f, false), 1.0f) << "0.99999994 rounds to 1";
  EXPECT_EQ(multiply(1.0f, 1.0f + 1.0f / 2048.0f, false), 1.0f) << "A is clamped to 1";
  EXPECT_EQ(multiply(1.0f, -0.5f, false), 0.0f) << "A is clamped to 0";
  EXPECT_EQ(multiply(1.0f + 1.0f / 1024.0f, 1.0f - 1.0f / 4096.0f, false), 1.0f + 1.0f / 1024.0f)
      << "1.000732: nearer 1.000977 than 1";
  EXPECT_EQ(multiply(2049.0f / 1024.0f, 0.5f, false), 2050.0f / 2048.0f) << "1 + 1/2048, halfway: away from zero";
  EXPECT_EQ(multiply(-2049.0f / 1024.0f, 0.5f, false), -2050.0f / 2048.0f) << "halfway, negative: away from zero";
  EXPECT_EQ(multiply(std::ldexp(1.0f, -24), 0.25f, false), 0.0f) << "below half the smallest subnormal";
  EXPECT_TRUE(std::isinf(multiply(INFINITY, 0.5f, false)));
  EXPECT_TRUE(std::isinf(multiply(-INFINITY, 0.0f, false)) && multiply(-INFINITY, 0.0f, false) < 0) << "kept, not NaN";
  EXPECT_TRUE(std::isnan(multiply(NAN, 0.5f, true)));
  // unorm8: the product rounded to the nearest 1/255.
  EXPECT_EQ(multiply(200.0f / 255.0f, 0.5f, true), 100.0f / 255.0f);
  EXPECT_EQ(multiply(201.0f / 255.0f, 0.5f, true), 101.0f / 255.0f) << "100.5 steps: halves up";
  EXPECT_EQ(multiply(1.0f, 1.0f, true), 1.0f);
  for (int k = 0; k <= 255; ++k) EXPECT_EQ(multiply(float(k) / 255.0f, 1.0f, true), float(k) / 255.0f) << k;
}

cpu::Result runWith(const DepthImage& depth, const Camera& camera, gen::Format format, std::uint32_t mask,
                    const FloatImage* initial, Precision precision, OutputBlend blend = OutputBlend::Replace) {
  cpu::Inputs in;
  in.depth = &depth;
  in.outputFormat = format;
  in.outputChannels = mask;
  in.outputBlend = blend;
  in.output = initial;
  cpu::Result r;
  const Status st = cpu::run(test::untunedMedium(), camera, in, {precision, 2}, r);  // the figures below were sized for it
  EXPECT_TRUE(st.ok()) << st.message;
  return r;
}

TEST(OutputFormat, SelectedChannelsHoldAAsTheFormatRoundsIt) {
  const Camera camera = testCamera(4, 1000.0, ClipDepth::NegativeOneToOne, false, 64, 40);
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D32F);
  const cpu::Result base = runWith(depth, camera, gen::Format::R16F, kAllChannels, nullptr, Precision::Float);
  const cpu::Result exact = runWith(depth, camera, gen::Format::R16F, kAllChannels, nullptr, Precision::Double);
  ASSERT_EQ(base.ao.channels, 1u);
  // The unrounded A of Float precision: binary16 rounding is within half a binary16 step of it.
  FloatImage initial(base.ao.extent, 4);
  for (std::size_t i = 0; i < initial.data.size(); ++i) initial.data[i] = float(i % 7) / 8.0f;
  for (gen::Format f : outputFormats()) {
    for (std::uint32_t mask : {kAllChannels, kChannelR, kChannelG | kChannelA}) {
      const std::uint32_t channels = channelCount(f);
      if (channels == 1 && mask == (kChannelG | kChannelA)) continue;
      SCOPED_TRACE(std::string(formatName(f)) + " mask " + std::to_string(mask));
      FloatImage init(base.ao.extent, channels);
      for (std::size_t i = 0; i < init.data.size(); ++i) init.data[i] = initial.data[i];
      const cpu::Result r = runWith(depth, camera, f, mask, &init, Precision::Float);
      const cpu::Result d = runWith(depth, camera, f, mask, &init, Precision::Double);
      ASSERT_EQ(r.ao.channels, channels);
      ASSERT_EQ(d.ao.channels, channels);
      const bool unorm = f == gen::Format::R8 || f == gen::Format::RGBA8;
      std::size_t wrong = 0, kept = 0;
      for (std::size_t p = 0; p < base.ao.data.size(); ++p)
        for (std::uint32_t c = 0; c < channels; ++c) {
          const float v = r.ao.data[p * channels + c], dv = d.ao.data[p * channels + c];
          if (((mask >> c) & 1u) == 0) {
            kept += v == init.data[p * channels + c] && dv == init.data[p * channels + c];
            continue;
          }
          const float expected = unorm ? std::floor(float(exact.ao.data[p]) * 255.0f + 0.5f) / 255.0f : base.ao.data[p];
          // Float's A and Double's differ by far less than a step, so the rounded values agree
          // except where A lies within that difference of a rounding boundary.
          if (std::fabs(v - expected) > (unorm ? 1.0f / 255.0f : 0.0f) + 1e-7f) ++wrong;
          if (unorm && v != float(std::lround(v * 255.0)) / 255.0f) ++wrong;  // exactly a step k / 255
          if (!unorm && v != base.ao.data[p]) ++wrong;  // the binary16 channels are the default output's bits
          if (std::fabs(dv - exact.ao.data[p]) != 0.0f) ++wrong;  // Double: unrounded A, whatever the format
        }
      EXPECT_EQ(wrong, 0u);
      std::size_t unselected = 0;
      for (std::uint32_t c = 0; c < channels; ++c) unselected += ((mask >> c) & 1u) == 0;
      EXPECT_EQ(kept, unselected * base.ao.data.size()) << "unselected channels keep the initial output";
    }
  }
}

// The multiply blend in the reference: Double stores initial x A (A unrounded, as the default
// output's Double run has it), Float the same product rounded once as the format holds it; the
// unselected channel (alpha) keeps the initial texel.
TEST(OutputFormat, MultiplyTakesTheInitialTexelTimesA) {
  const Camera camera = testCamera(4, 1000.0, ClipDepth::NegativeOneToOne, false, 64, 40);
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D32F);
  const cpu::Result exact = runWith(depth, camera, gen::Format::R16F, kAllChannels, nullptr, Precision::Double);
  const std::uint32_t rgb = kChannelR | kChannelG | kChannelB;
  for (gen::Format f : {gen::Format::RGBA16F, gen::Format::RGBA8}) {
    SCOPED_TRACE(formatName(f));
    const bool unorm = f == gen::Format::RGBA8;
    FloatImage init(exact.ao.extent, 4);
    for (std::size_t i = 0; i < init.data.size(); ++i)
      init.data[i] = unorm ? float(i % 256) / 255.0f : float(int(i % 256) - 32) / 4.0f;  // HDR, negatives
    const cpu::Result d = runWith(depth, camera, f, rgb, &init, Precision::Double, OutputBlend::Multiply);
    const cpu::Result r = runWith(depth, camera, f, rgb, &init, Precision::Float, OutputBlend::Multiply);
    std::size_t wrong = 0, changed = 0;
    for (std::size_t p = 0; p < exact.ao.data.size(); ++p)
      for (std::size_t c = 0; c < 4; ++c) {
        const std::size_t i = p * 4 + c;
        if (c == 3) {
          wrong += d.ao.data[i] != init.data[i] || r.ao.data[i] != init.data[i];
          continue;
        }
        // The Double run's A (stored as float here) times the texel: Double's own product, of its
        // unrounded A, stored as float, is within two float ulps of it.
        const double product = double(init.data[i]) * double(exact.ao.data[p]);
        wrong += std::fabs(d.ao.data[i] - product) > std::fabs(product) * 0x1p-22;
        changed += r.ao.data[i] != init.data[i];
        // Float's A differs from Double's by far less than a step: the rounded product is within
        // one step of the exact one (unorm8: 1/255; binary16: the spacing at the product).
        const double step =
            unorm ? 1.0 / 255.0 : std::ldexp(1.0, std::max(std::ilogb(std::max(std::fabs(product), 6.1e-5)) - 10, -24));
        wrong += std::fabs(r.ao.data[i] - product) > step;
        if (unorm) wrong += r.ao.data[i] != float(std::lround(r.ao.data[i] * 255.0)) / 255.0f;
      }
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(changed, exact.ao.data.size()) << "the multiply changed too few texels: nothing compared";
  }
}

TEST(OutputFormat, BadFormatsMasksAndInitialOutputsAreRefused) {
  const Camera camera = testCamera(0, 1000.0, ClipDepth::NegativeOneToOne, false, 16, 9);
  const DepthImage depth = renderDepth(planeScene(3.0), camera, DepthFormat::D32F);
  cpu::Inputs in;
  in.depth = &depth;
  cpu::Result r;
  in.outputFormat = gen::Format::RG16F;
  Status st = cpu::run(Settings{}, camera, in, {}, r);
  EXPECT_EQ(st.code, StatusCode::UnsupportedFormat);
  EXPECT_NE(st.message.find("rg16f"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("r16f, r8, rgba8, rgba16f"), std::string::npos) << st.message;
  in.outputFormat = gen::Format::R8;
  in.outputChannels = kChannelB;
  st = cpu::run(Settings{}, camera, in, {}, r);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  in.outputFormat = gen::Format::RGBA8;
  in.outputChannels = 0;
  EXPECT_EQ(cpu::run(Settings{}, camera, in, {}, r).code, StatusCode::InvalidInput);
  in.outputChannels = kChannelA;
  const FloatImage wrongChannels({16, 9}, 1), wrongSize({16, 8}, 4);
  in.output = &wrongChannels;
  EXPECT_EQ(cpu::run(Settings{}, camera, in, {}, r).code, StatusCode::InvalidInput);
  in.output = &wrongSize;
  EXPECT_EQ(cpu::run(Settings{}, camera, in, {}, r).code, StatusCode::InvalidInput);
  in.output = nullptr;
  in.outputBlend = OutputBlend::Multiply;
  st = cpu::run(Settings{}, camera, in, {}, r);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  EXPECT_NE(st.message.find("output blend multiply needs your own output"), std::string::npos) << st.message;
  const FloatImage right({16, 9}, 4, 0.5f);
  in.output = &right;
  st = cpu::run(Settings{}, camera, in, {}, r);
  EXPECT_TRUE(st.ok()) << st.message;
  in.outputBlend = static_cast<OutputBlend>(2);
  st = cpu::run(Settings{}, camera, in, {}, r);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  EXPECT_NE(st.message.find("unknown output blend 2"), std::string::npos) << st.message;
}

}  // namespace
}  // namespace sao::test
