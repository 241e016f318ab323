// A multisampled depth input read directly (Config::depthSamples, DEPTH_MULTISAMPLE), under
// validation and synchronization validation: a 4-sample D32_SFLOAT image holding, per sample, one
// of three scenes (tests/cpu/msaa_depth.h; written by rendering, msaa_depth_writer.h) is the
// effect's depth for both Camera::depthSamplePolicy values and two depth conventions. Against the
// CPU reference (Float) on the same samples: the parameter block byte for byte, csz level 0 bit for
// bit, the final and raw AO within reference_test.cpp's bounds (99.9 % within 2/255, none beyond
// 4/255). Independently of the reference: Sample0 gives the bits of the single-sample effect on
// sample 0, and Nearest's csz level 0 is, texel by texel, the nearer of the four single-sample
// runs' csz (sky only where all are sky); the two policies differ on many texels. create() refuses
// a count that is not one sample bit, a multisampled input with a second layer, and counts the
// device cannot sample.
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "analytic_scenes.h"
#include "msaa_depth.h"
#include "msaa_depth_writer.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;  // reference_test.cpp's bounds
constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8, kSamples = 4;
constexpr auto kMultisample = static_cast<std::size_t>(gen::VariantId::DEPTH_MULTISAMPLE);

struct Convention {
  const char* name;
  Camera camera;
  VkImageLayout layout;  // the depth image's layout when the effect reads it
};

std::vector<Convention> conventions() {
  return {{"reversed_infinite", vulkanCamera(kW, kH, kGuard, INFINITY, /*reversedZ=*/true),
           VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
          {"standard_far100", vulkanCamera(kW, kH, kGuard, 100.0), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
}

// Per sample one of: the sphere on its plane, the rods, the sky (silhouettes and sky mixed in texels).
DepthImage msaaDepth(const Camera& camera) {
  const DepthImage a = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
  const DepthImage b = test::renderDepth(test::rodsScene(), camera, DepthFormat::D32F);
  const DepthImage c = test::renderDepth(test::skyScene(), camera, DepthFormat::D32F);
  return test::interleaveSamples({&a, &b, &c}, kSamples);
}

Camera withPolicy(Camera c, DepthSamplePolicy p) {
  c.depthSamplePolicy = p;
  return c;
}

std::size_t bitDifferences(const FloatImage& a, const FloatImage& b) {
  EXPECT_EQ(a.data.size(), b.data.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i)
    n += std::bit_cast<std::uint32_t>(a.data[i]) != std::bit_cast<std::uint32_t>(b.data[i]);
  return n;
}

// csz geometry: finite z < 0 (+0.0 is the sky marker; the effect's sao_is_sky).
bool geometry(float z) {
  const std::uint32_t b = std::bit_cast<std::uint32_t>(z);
  return b > 0x80000000u && b < 0xFF800000u;
}

// Holds the multisampled image for one convention; destroyed with it.
struct MsaaImage {
  vk::headless::Image image;
  ~MsaaImage() { context().destroy(image); }
};

RunOptions msaaOptions(const MsaaImage& m, VkImageLayout layout) {
  RunOptions o;
  o.depthLayout = layout;
  o.depthImage = vk::InputImage{m.image.view, layout, m.image.extent, VK_FORMAT_D32_SFLOAT};
  o.depthSamples = VK_SAMPLE_COUNT_4_BIT;
  return o;
}

class MsaaDepth : public VkTest {};

TEST_F(MsaaDepth, BothPoliciesMatchTheCpuReference) {
  for (int estimator : {0, 1}) {  // 1: the visibility estimator, with thickness from width
    Settings settings = presetSettings(Preset::Medium);
    settings.estimator = estimator;
    settings.thickness_model = estimator;
    SCOPED_TRACE("estimator " + std::to_string(estimator));
    for (const Convention& conv : conventions()) {
      SCOPED_TRACE(conv.name);
      const DepthImage depth = msaaDepth(conv.camera);
      MsaaImage msaa;
      const Status ws = writeMultisampledDepth(context(), depth, conv.layout, msaa.image);
      ASSERT_TRUE(ws.ok()) << ws.message;

      RunResult vkRuns[2];
      const DepthSamplePolicy policies[2] = {DepthSamplePolicy::Sample0, DepthSamplePolicy::Nearest};
      for (int i = 0; i < 2; ++i) {
        const char* policyName = i == 0 ? "Sample0" : "Nearest";
        SCOPED_TRACE(policyName);
        const Camera camera = withPolicy(conv.camera, policies[i]);
        RunResult& vk = vkRuns[i];
        const Status st = runEffect(settings, camera, depth, VkDepth::D32F, vk, msaaOptions(msaa, conv.layout));
        ASSERT_TRUE(st.ok()) << st.message;
        EXPECT_EQ(vk.plan.variants[kMultisample], 1) << "DEPTH_MULTISAMPLE";

        cpu::Inputs in;
        in.depth = &depth;
        cpu::Result ref;
        const Status cs = cpu::run(settings, camera, in, {cpu::Precision::Float, 2}, ref);
        ASSERT_TRUE(cs.ok()) << cs.message;
        EXPECT_EQ(ref.plan.variants[kMultisample], 1) << "the CPU reference's DEPTH_MULTISAMPLE";
        EXPECT_EQ(vk.params.depth_samples, 4);
        EXPECT_EQ(vk.params.depth_sample_policy, int(policies[i]));
        EXPECT_EQ(std::memcmp(&vk.params, &ref.params, sizeof(ParamBlock)), 0) << "same parameter block";

        const std::size_t cszDiff = bitDifferences(vk.csz0, ref.csz[0]);
        EXPECT_EQ(cszDiff, 0u) << "csz level 0 bit for bit";
        const std::string name = std::string("vk_cpu_msaa_") + conv.name + "_" + policyName;
        std::string noteF, noteR;
        const Agreement f = compare(vk.ao, ref.ao, 0, kWithin, kNever, name + "_final", &noteF);
        const Agreement r = compare(vk.aoRaw, ref.aoRaw, 0, kWithin, kNever, name + "_raw", &noteR);
        EXPECT_TRUE(acceptable(f)) << "final AO: " << f.fractionWithin * 100 << "% within 2/255, " << f.beyond
                                   << " beyond 4/255, max " << f.maxAbs * 255 << "/255. " << noteF;
        EXPECT_TRUE(acceptable(r)) << "raw AO: " << r.fractionWithin * 100 << "% within 2/255, " << r.beyond
                                   << " beyond 4/255, max " << r.maxAbs * 255 << "/255. " << noteR;
        std::printf("msaa %-17s %-7s final max %.3g p999 %.3g within 2/255 %.3f%% | raw max %.3g p999 %.3g | "
                    "csz0 bits differ %zu of %zu\n",
                    conv.name, policyName, f.maxAbs, f.p999, f.fractionWithin * 100, r.maxAbs, r.p999, cszDiff,
                    vk.csz0.data.size());
      }

      // The same effect on each sample alone, single-sample: Sample0 must be its sample-0 run bit for
      // bit (only linear_z reads differently), Nearest the nearer of the four runs' csz per texel.
      FloatImage nearest;
      for (std::uint32_t s = 0; s < kSamples; ++s) {
        const DepthImage one = test::sampleImage(depth, s);
        RunResult single;
        const Status st = runEffect(settings, conv.camera, one, VkDepth::D32F, single);
        ASSERT_TRUE(st.ok()) << st.message;
        EXPECT_EQ(single.plan.variants[kMultisample], 0);
        if (s == 0) {
          EXPECT_TRUE(test::sameBits(vkRuns[0].csz0, single.csz0)) << "Sample0: csz of the sample-0 image";
          EXPECT_TRUE(test::sameBits(vkRuns[0].aoRaw, single.aoRaw)) << "Sample0: raw AO of the sample-0 image";
          EXPECT_TRUE(test::sameBits(vkRuns[0].ao, single.ao)) << "Sample0: final AO of the sample-0 image";
          nearest = single.csz0;
          continue;
        }
        ASSERT_EQ(single.csz0.data.size(), nearest.data.size());
        for (std::size_t i = 0; i < nearest.data.size(); ++i) {
          const float z = single.csz0.data[i];
          float& n = nearest.data[i];
          if (geometry(z) && (!geometry(n) || z > n)) n = z;
        }
      }
      const std::size_t nearestDiff = bitDifferences(vkRuns[1].csz0, nearest);
      EXPECT_EQ(nearestDiff, 0u) << "Nearest: the nearer of the single-sample runs' csz";

      // Not vacuous: sample 0 is not the nearest sample in many texels.
      const std::size_t texels = vkRuns[0].csz0.data.size();
      const std::size_t policyDiff = bitDifferences(vkRuns[0].csz0, vkRuns[1].csz0);
      const std::size_t aoDiff = bitDifferences(vkRuns[0].ao, vkRuns[1].ao);
      EXPECT_GT(policyDiff, texels / 10) << "Sample0 and Nearest csz differ on too few texels";
      EXPECT_GT(aoDiff, 0u) << "Sample0 and Nearest give the same AO";
      std::printf("msaa %-17s Sample0 vs Nearest: csz0 differs on %zu of %zu texels, final AO on %zu of %zu; "
                  "Nearest vs the single-sample runs' nearer csz: %zu differ\n",
                  conv.name, policyDiff, texels, aoDiff, vkRuns[0].ao.data.size(), nearestDiff);
    }
  }
}

vk::Config msaaConfig(VkFormat format, VkSampleCountFlagBits samples) {
  vk::Config c;
  c.camera = vulkanCamera(kW, kH, kGuard, 100.0);
  c.settings = presetSettings(Preset::Medium);
  c.depthFormat = format;
  c.depthSamples = samples;
  return c;
}

TEST_F(MsaaDepth, CreateRefusesBadSampleCounts) {
  std::unique_ptr<vk::Effect> effect;
  {
    const Status st = vk::Effect::create(context().deviceContext(),
                                         msaaConfig(VK_FORMAT_D32_SFLOAT, static_cast<VkSampleCountFlagBits>(3)), effect);
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    EXPECT_NE(st.message.find("depthSamples"), std::string::npos) << st.message;
    EXPECT_EQ(effect, nullptr);
  }
  {
    vk::Config c = msaaConfig(VK_FORMAT_D32_SFLOAT, VK_SAMPLE_COUNT_4_BIT);
    c.secondLayer = true;
    const Status st = vk::Effect::create(context().deviceContext(), c, effect);
    EXPECT_FALSE(st.ok());
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    EXPECT_NE(st.message.find("secondLayer"), std::string::npos) << st.message;
    EXPECT_NE(st.message.find("second layer"), std::string::npos) << st.message;
    EXPECT_EQ(effect, nullptr);
  }
  // Each count against the device's limit for the format: refused exactly where it cannot sample it.
  const auto& limits = context().properties().limits;
  for (const auto& [format, counts, what] :
       {std::tuple{VK_FORMAT_D32_SFLOAT, limits.sampledImageDepthSampleCounts, "D32_SFLOAT"},
        std::tuple{VK_FORMAT_R32_SFLOAT, limits.sampledImageColorSampleCounts, "R32_SFLOAT"}}) {
    std::printf("%s: sampled image sample counts 0x%x\n", what, unsigned(counts));
    for (std::uint32_t n = 2; n <= 64; n *= 2) {
      SCOPED_TRACE(std::string(what) + " " + std::to_string(n) + " samples");
      const Status st =
          vk::Effect::create(context().deviceContext(), msaaConfig(format, static_cast<VkSampleCountFlagBits>(n)), effect);
      if (counts & n) {
        ASSERT_TRUE(st.ok()) << st.message;
        EXPECT_EQ(effect->plan().variants[kMultisample], 1);
        EXPECT_EQ(effect->params().depth_samples, int(n));
      } else {
        EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
        EXPECT_NE(st.message.find("depthSamples"), std::string::npos) << st.message;
        EXPECT_EQ(effect, nullptr);
      }
      effect.reset();
    }
  }
}

}  // namespace
}  // namespace sao::vktest
