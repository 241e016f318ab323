// Multisampled depth read directly (Camera::depthSamplePolicy, DEPTH_MULTISAMPLE) on each API: a
// 4-sample D32F depth whose samples mix three scenes (tests/cpu/msaa_depth.h), written sample by
// sample by the harness (GL: GL_TEXTURE_2D_MULTISAMPLE; Vulkan: InputImage::samples). For both
// policies, both estimators and three depth conventions, against the CPU reference on the same
// samples: the parameter block, csz level 0 bit for bit, final and raw AO within the agreement
// bounds. Independently of the reference: Sample0 is the single-sample run on sample 0 bit for bit,
// Nearest's csz level 0 the nearer of the four single-sample runs' (sky only where all are sky), and
// the policies differ on many texels. A second depth layer is refused. GL's bindings and
// multisampled textures, Vulkan's sample counts: tests/gl and tests/vulkan msaa_depth_test.cpp.
#include <bit>
#include <cstdio>
#include <string>

#include "harness.h"
#include "msaa_depth.h"
#include "sao/presets.h"

namespace sao::exectest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8, kSamples = 4;
constexpr auto kMultisample = std::size_t(gen::VariantId::DEPTH_MULTISAMPLE);

struct Convention {
  std::string name;
  Camera camera;
  bool depthReadOnlyLayout = false;  // Vulkan's layout for the depth; GL has none
};
std::string caseName(const Convention& c) { return c.name; }
void PrintTo(const Convention& c, std::ostream* os) { *os << c.name; }
std::vector<Convention> conventions() {
  return {{"opengl_far1000", test::openglCamera(kW, kH, kGuard)},
          {"reversed_infinite", test::vulkanCamera(kW, kH, kGuard, INFINITY, /*reversedZ=*/true), true},
          {"standard_far100", test::vulkanCamera(kW, kH, kGuard, 100.0)}};
}

// Per sample one of: the sphere on its plane, the rods, the sky (silhouettes and sky mixed in texels).
DepthImage msaaDepth(const Camera& camera) {
  const DepthImage a = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
  const DepthImage b = test::renderDepth(test::rodsScene(), camera, DepthFormat::D32F);
  const DepthImage c = test::renderDepth(test::skyScene(), camera, DepthFormat::D32F);
  return test::interleaveSamples({&a, &b, &c}, kSamples);
}

// csz geometry: finite z < 0 (+0.0 is the sky marker; the effect's sao_is_sky).
bool geometry(float z) {
  const std::uint32_t b = std::bit_cast<std::uint32_t>(z);
  return b > 0x80000000u && b < 0xFF800000u;
}

using MsaaDepth = ApiCaseTest<Convention>;
TEST_P(MsaaDepth, BothPoliciesMatchTheCpuReferenceAndTheSingleSampleRuns) {
  const DepthImage depth = msaaDepth(param().camera);
  for (int estimator : {0, 1}) {  // 1: the visibility estimator, with thickness from width
    SCOPED_TRACE("estimator " + std::to_string(estimator));
    Frame f;
    f.settings = presetSettings(Preset::Medium);
    f.settings.estimator = f.settings.thickness_model = estimator;
    f.depth = &depth;
    f.depthReadOnlyLayout = param().depthReadOnlyLayout;
    auto e = make();
    FloatImage csz[2], ao[2], raw[2];
    for (DepthSamplePolicy policy : {DepthSamplePolicy::Sample0, DepthSamplePolicy::Nearest}) {
      const int i = int(policy);
      const std::string name = param().name + (i == 0 ? "_sample0" : "_nearest") + "_estimator" + std::to_string(estimator);
      SCOPED_TRACE(name);
      f.camera = param().camera;
      f.camera.depthSamplePolicy = policy;
      const Status st = e->render(f);
      ASSERT_TRUE(st.ok()) << st.message;
      cpu::Result ref;
      const Status cs = runCpu(f, ref);
      ASSERT_TRUE(cs.ok()) << cs.message;
      EXPECT_EQ(e->plan().variants[kMultisample], 1);
      EXPECT_EQ(ref.plan.variants[kMultisample], 1) << "the CPU reference's DEPTH_MULTISAMPLE";
      EXPECT_EQ(e->params().depth_samples, int(kSamples));
      EXPECT_EQ(e->params().depth_sample_policy, i);
      csz[i] = e->image(gen::ResourceId::csz);
      EXPECT_EQ(test::differingValues(csz[i], ref.csz[0]), 0u) << "csz level 0 bit for bit";
      expectAgreesWithCpu(*e, ref, "msaa_" + name);  // the parameter block, final and raw AO
      ao[i] = e->output();
      raw[i] = e->image(gen::ResourceId::ao_raw);
    }

    // Each sample alone, single-sample: Sample0 is the sample-0 run bit for bit (only linear_z reads
    // differently), Nearest's csz the nearer of the four runs' per texel.
    FloatImage nearest;
    auto single = make();
    for (std::uint32_t s = 0; s < kSamples; ++s) {
      const DepthImage one = test::sampleImage(depth, s);
      Frame sf = f;
      sf.camera = param().camera;
      sf.depth = &one;
      sf.depthReadOnlyLayout = false;
      const Status st = single->render(sf);
      ASSERT_TRUE(st.ok()) << st.message;
      EXPECT_EQ(single->plan().variants[kMultisample], 0);
      const FloatImage oneCsz = single->image(gen::ResourceId::csz);
      if (s == 0) {
        EXPECT_TRUE(test::sameBits(csz[0], oneCsz)) << "Sample0: csz of the sample-0 image";
        EXPECT_TRUE(test::sameBits(raw[0], single->image(gen::ResourceId::ao_raw))) << "Sample0: raw AO of sample 0";
        EXPECT_TRUE(test::sameBits(ao[0], single->output())) << "Sample0: final AO of the sample-0 image";
        nearest = oneCsz;
        continue;
      }
      ASSERT_EQ(oneCsz.data.size(), nearest.data.size());
      for (std::size_t t = 0; t < nearest.data.size(); ++t)
        if (geometry(oneCsz.data[t]) && (!geometry(nearest.data[t]) || oneCsz.data[t] > nearest.data[t]))
          nearest.data[t] = oneCsz.data[t];
    }
    const std::size_t nearestDiff = test::differingValues(csz[1], nearest);
    EXPECT_EQ(nearestDiff, 0u) << "Nearest: the nearer of the single-sample runs' csz";
    // Not vacuous: sample 0 is not the nearest sample in many texels.
    const std::size_t policyDiff = test::differingValues(csz[0], csz[1]), aoDiff = test::differingValues(ao[0], ao[1]);
    EXPECT_GT(policyDiff, csz[0].data.size() / 4) << "Sample0 and Nearest csz differ on too few texels";
    EXPECT_GT(aoDiff, 0u) << "Sample0 and Nearest give the same AO";
    std::printf("MSAA %-7s %-17s estimator %d: Sample0 vs Nearest csz0 differs on %zu of %zu texels, final AO on %zu; "
                "Nearest vs the single-sample runs' nearer csz: %zu differ\n",
                toString(api()), param().name.c_str(), estimator, policyDiff, csz[0].data.size(), aoDiff, nearestDiff);
  }
}
SAO_INSTANTIATE_API_CASES(MsaaDepth, conventions());

// A multisampled depth has no second layer (depth2 is single-sample only): refused, nothing made.
using MsaaDepthRefusal = ApiTest;
TEST_P(MsaaDepthRefusal, ASecondLayerIsRefused) {
  Frame f;
  f.settings = presetSettings(Preset::Medium);
  f.camera = test::vulkanCamera(kW, kH, kGuard, 100.0);
  const DepthImage depth = msaaDepth(f.camera), single = test::sampleImage(depth, 0);
  f.depth = &depth;
  f.depth2 = &single;
  auto e = make();
  const Status st = e->render(f);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  EXPECT_NE(st.message.find("second layer"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("multisampled depth input has no second layer"), std::string::npos) << st.message;
  if (api() == Api::Vulkan) {  // names the member that says it: the depth's InputImage::samples
    EXPECT_NE(st.message.find("depth.samples is 4"), std::string::npos) << st.message;
  }
  EXPECT_EQ(e->imageAllocations(), 0u) << "nothing made for the refused frame";
}
SAO_INSTANTIATE_APIS(MsaaDepthRefusal);

}  // namespace
}  // namespace sao::exectest
