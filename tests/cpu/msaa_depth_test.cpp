// A multisampled depth input on the CPU reference (DepthImage::samples, Camera::depthSamplePolicy,
// the DEPTH_MULTISAMPLE variant): Sample0 gives exactly the single-sample run on sample 0; Nearest
// keeps, per texel, the sample nearest to the camera (sky only when every sample is sky), which is
// exactly the single-sample run on the image of those samples; refusals name the problem.
#include <vector>

#include "msaa_depth.h"
#include "sao/presets.h"
#include "test_support.h"

namespace sao::test {
namespace {

using cpu::Precision;

constexpr std::uint32_t kSamples = 4;

struct Layers {
  Camera camera = testCamera(8);
  DepthImage sphere, rods, sky, msaa;
  explicit Layers(DepthFormat format) {
    sphere = renderDepth(sphereOnPlaneScene(), camera, format);
    rods = renderDepth(rodsScene(), camera, format);
    sky = renderDepth(skyScene(), camera, format);
    msaa = interleaveSamples({&sphere, &rods, &sky}, kSamples);
  }
};

cpu::Result run(const Camera& camera, const DepthImage& depth, Precision precision) {
  cpu::Inputs in;
  in.depth = &depth;
  return runOrFail(presetSettings(Preset::Medium), camera, in, precision);
}

TEST(MsaaDepth, Sample0IsTheSingleSampleRunOnSampleZero) {
  for (DepthFormat format : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ}) {
    SCOPED_TRACE(toString(format));
    const Layers l(format);
    for (Precision precision : {Precision::Float, Precision::Double}) {
      const cpu::Result ms = run(l.camera, l.msaa, precision);
      const cpu::Result s0 = run(l.camera, sampleImage(l.msaa, 0), precision);
      EXPECT_EQ(ms.plan.variants[std::size_t(gen::VariantId::DEPTH_MULTISAMPLE)], 1);
      EXPECT_EQ(s0.plan.variants[std::size_t(gen::VariantId::DEPTH_MULTISAMPLE)], 0);
      EXPECT_EQ(ms.params.depth_samples, std::int32_t(kSamples));
      EXPECT_EQ(differingValues(ms.csz[0], s0.csz[0]), 0u);
      EXPECT_EQ(differingValues(ms.ao, s0.ao), 0u);
    }
  }
}

TEST(MsaaDepth, NearestKeepsTheNearestSampleOfEachTexel) {
  for (DepthFormat format : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ}) {
    SCOPED_TRACE(toString(format));
    const Layers l(format);
    Camera nearest = l.camera;
    nearest.depthSamplePolicy = DepthSamplePolicy::Nearest;
    // Each sample alone, through the single-sample path.
    std::vector<cpu::Result> perSample;
    for (std::uint32_t s = 0; s < kSamples; ++s) perSample.push_back(run(l.camera, sampleImage(l.msaa, s), Precision::Float));
    const cpu::Result ms = run(nearest, l.msaa, Precision::Float);
    const Extent e = l.msaa.extent;
    DepthImage chosen = sampleImage(l.msaa, 0);  // per texel, the raw value of the nearest sample
    std::size_t wrong = 0, notSample0 = 0, allSky = 0, mixedSky = 0;
    for (std::uint32_t y = 0; y < e.height; ++y)
      for (std::uint32_t x = 0; x < e.width; ++x) {
        std::uint32_t best = 0, sky = 0;
        for (std::uint32_t s = 0; s < kSamples; ++s) {
          const float z = perSample[s].csz[0].at(x, y), zb = perSample[best].csz[0].at(x, y);
          sky += z == 0.0f;
          if (z != 0.0f && (zb == 0.0f || z > zb)) best = s;
        }
        const float want = perSample[best].csz[0].at(x, y);
        wrong += std::bit_cast<std::uint32_t>(ms.csz[0].at(x, y)) != std::bit_cast<std::uint32_t>(want);
        notSample0 += want != perSample[0].csz[0].at(x, y);
        allSky += sky == kSamples;
        mixedSky += sky > 0 && sky < kSamples;
        chosen.texels[std::size_t(y) * e.width + x] = l.msaa.raw(x, y, best);
      }
    EXPECT_EQ(wrong, 0u);
    // Not vacuous: many texels keep another sample than 0, some are all sky, some mix sky and geometry.
    EXPECT_GT(notSample0, std::size_t(e.width) * e.height / 4);
    EXPECT_GT(allSky, 0u);
    EXPECT_GT(mixedSky, 0u);
    // The whole effect after linear_z is the single-sample effect on the chosen samples.
    const cpu::Result one = run(l.camera, chosen, Precision::Float);
    EXPECT_EQ(differingValues(ms.ao, one.ao), 0u);
    // Double precision picks the same samples here (no two samples of a texel within float rounding).
    const cpu::Result msd = run(nearest, l.msaa, Precision::Double);
    const cpu::Result oned = run(l.camera, chosen, Precision::Double);
    EXPECT_EQ(differingValues(msd.ao, oned.ao), 0u);
  }
}

TEST(MsaaDepth, OneSampleIsTheSingleSamplePath) {
  const Layers l(DepthFormat::D32F);
  DepthImage one = interleaveSamples({&l.sphere}, 1);
  Camera nearest = l.camera;
  nearest.depthSamplePolicy = DepthSamplePolicy::Nearest;  // one sample: nothing to choose
  const cpu::Result a = run(nearest, one, Precision::Float);
  const cpu::Result b = run(l.camera, l.sphere, Precision::Float);
  EXPECT_EQ(a.plan.variants[std::size_t(gen::VariantId::DEPTH_MULTISAMPLE)], 0);
  EXPECT_EQ(differingValues(a.ao, b.ao), 0u);
}

TEST(MsaaDepth, BadInputsAreRefused) {
  const Layers l(DepthFormat::D32F);
  const Settings settings = presetSettings(Preset::Medium);
  auto refused = [&](const Camera& camera, const cpu::Inputs& in, StatusCode code, const std::string& words) {
    cpu::Result r;
    const Status st = cpu::run(settings, camera, in, {Precision::Float, 2}, r);
    EXPECT_FALSE(st.ok());
    EXPECT_EQ(st.code, code) << st.message;
    EXPECT_NE(st.message.find(words), std::string::npos) << st.message;
  };
  cpu::Inputs in;
  DepthImage zero = l.msaa;
  zero.samples = 0;
  in.depth = &zero;
  refused(l.camera, in, StatusCode::InvalidInput, "0 samples per texel");
  DepthImage shortOne = l.msaa;
  shortOne.texels.pop_back();
  in.depth = &shortOne;
  refused(l.camera, in, StatusCode::InvalidInput, "with 4 samples per texel needs");
  // A multisampled depth has no second layer (the effect's exclusion names why).
  in.depth = &l.msaa;
  in.depth2 = &l.rods;
  refused(l.camera, in, StatusCode::InvalidInput, "multisampled depth input has no second layer");
  in.depth2 = nullptr;
  Camera bad = l.camera;
  bad.depthSamplePolicy = static_cast<DepthSamplePolicy>(7);
  refused(bad, in, StatusCode::InvalidCamera, "depthSamplePolicy = 7");
}

TEST(MsaaDepth, FileDepthCheckNamesTheSample) {
  const Layers l(DepthFormat::D32F);
  DepthImage bad = l.msaa;
  bad.texels[(std::size_t(3) * bad.extent.width + 5) * kSamples + 2] = std::bit_cast<std::uint32_t>(2.0f);
  const Status st = checkDepthValues(bad);
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message.find("(5, 3) sample 2"), std::string::npos) << st.message;
}

}  // namespace
}  // namespace sao::test
