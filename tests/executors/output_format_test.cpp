// The output as the engine wants it (sao/output.h) on each API: the caller's R16F, R8, RGBA8 and
// RGBA16F output with channel masks and the multiply blend (the apply step, also on an HDR colour
// target with infinities and NaNs) against the CPU reference (Float) at full and half resolution
// (upsample writes the output at both) and albedo 0 and 0.6, under GL's and Vulkan's usual
// cameras; untouched channels keep their sentinel texels; an RGBA16F output holds the owned
// output's bits; bad masks and blends are refused naming them; outputGeneration() follows the
// owned output. GLES stores an R16F output as GL_R32F and refuses an R8 one (refusesOutput).
// Formats each API refuses by its own names, Vulkan layouts and owned outputs in other formats, and
// GL texture names: tests/gl and tests/vulkan output_format_test.cpp.
#include <string>

#include "harness.h"
#include "output_format_check.h"
#include "sao/presets.h"

namespace sao::exectest {
namespace {

Settings settingsFor(int divisor, float albedo = 0) {
  Settings s = presetSettings(Preset::Medium);
  s.resolution_divisor = divisor;
  s.albedo = albedo;  // > 0: the multi-bounce fit in the store (docs/effect-math.md 9)
  return s;
}

Frame frameInto(const Camera& camera, const DepthImage& depth, Settings settings, Output output) {
  Frame f;
  f.settings = settings;
  f.camera = camera;
  f.depth = &depth;
  f.output = output;
  return f;
}

struct CameraCase {
  std::string name;
  Camera camera;
};
std::string caseName(const CameraCase& c) { return c.name; }
void PrintTo(const CameraCase& c, std::ostream* os) { *os << c.name; }
const CameraCase kCameras[] = {{"opengl", test::openglCamera(160, 90, 8)},
                               {"reversed_infinite", test::vulkanCamera(160, 90, 8, INFINITY, /*reversedZ=*/true)}};

using OutputFormat = ApiCaseTest<CameraCase>;

TEST_P(OutputFormat, EveryFormatAndMaskMatchesTheCpuReference) {
  const Camera& cam = param().camera;
  const DepthImage depth = test::renderDepth(sceneByName("sphere"), cam, DepthFormat::D32F);
  const auto compareOn = [a = api()](const FloatImage& actual, const FloatImage& expected, std::uint32_t c,
                                     double within, double never, const std::string& name) {
    return compare(a, actual, expected, c, within, never, name);
  };
  auto e = make();
  for (int divisor : {1, 2})
    for (float albedo : {0.0f, 0.6f})
      for (const test::OutputCase& oc : test::kOutputCases) {
        const std::string name = std::string(toString(api())) + "_" + param().name + "_" + test::caseName(oc) + "_d" +
                                 std::to_string(divisor) + (albedo > 0 ? "_bounce" : "");
        SCOPED_TRACE(name);
        const FloatImage sentinel = test::sentinelOutput({cam.width, cam.height}, oc.format);
        const Frame f = frameInto(cam, depth, settingsFor(divisor, albedo), {true, oc.format, &sentinel, oc.mask, oc.blend});
        const Status st = e->render(f);
        if (refusesOutput(api(), oc.format)) {
          EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
          continue;
        }
        ASSERT_TRUE(st.ok()) << st.message;
        cpu::Result ref;
        ASSERT_TRUE(runCpu(f, ref).ok());
        EXPECT_EQ(e->plan().variants, ref.plan.variants) << "the same OUTPUT_FORMAT variant";
        test::checkOutput(e->output(), ref.ao, sentinel, oc.format, oc.mask, compareOn, name);
      }
}

// The apply step on an engine's HDR colour target: RGB multiplied by A, not clamped, infinities and
// NaNs stored back, alpha kept, at full and half resolution.
TEST_P(OutputFormat, MultiplyIntoAnHdrColourTarget) {
  const Camera& cam = param().camera;
  const DepthImage depth = test::renderDepth(sceneByName("sphere"), cam, DepthFormat::D32F);
  const FloatImage colour = test::hdrColour({cam.width, cam.height});
  auto e = make();
  for (int divisor : {1, 2}) {
    const Frame f = frameInto(cam, depth, settingsFor(divisor),
                              {true, gen::Format::RGBA16F, &colour, kChannelR | kChannelG | kChannelB, OutputBlend::Multiply});
    const Status st = e->render(f);
    ASSERT_TRUE(st.ok()) << st.message;
    cpu::Result ref;
    ASSERT_TRUE(runCpu(f, ref).ok());
    test::checkHdrMultiply(e->output(), ref.ao, colour,
                           std::string(toString(api())) + "_" + param().name + "_hdr_d" + std::to_string(divisor));
  }
}
SAO_INSTANTIATE_API_CASES(OutputFormat, kCameras);

using OutputFormatContract = ApiTest;

// The R16F path of an RGBA16F output is the owned output's: the same binary16 values.
TEST_P(OutputFormatContract, Rgba16fChannelsHoldTheDefaultOutputBits) {
  const Camera cam = test::openglCamera(96, 54, 4);
  const DepthImage depth = test::renderDepth(sceneByName("stairs"), cam, DepthFormat::D32F);
  auto e = make();
  ASSERT_TRUE(e->render(frameInto(cam, depth, settingsFor(1), {})).ok());
  const FloatImage r16 = e->output();
  ASSERT_TRUE(e->render(frameInto(cam, depth, settingsFor(1), {true, gen::Format::RGBA16F})).ok());
  const FloatImage rgba = e->output();
  ASSERT_EQ(rgba.data.size(), r16.data.size() * 4);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < r16.data.size(); ++i)
    for (std::size_t c = 0; c < 4; ++c) differ += rgba.data[i * 4 + c] != r16.data[i];
  EXPECT_EQ(differ, 0u);
}

// Masks and blends are per frame on every API: a bad one is refused naming it (and the call), the
// effect usable afterwards. The owned output is R16F: a mask keeping channels does not fit it, and
// a multiply has nothing to multiply. An output format the API refuses is left out (its refusal
// comes first: the test above).
TEST_P(OutputFormatContract, BadMasksAndBlendsAreRefused) {
  const Camera cam = test::openglCamera(32, 18, 0);
  const DepthImage depth = test::renderDepth(sceneByName("plane"), cam, DepthFormat::D32F);
  struct BadUse {
    Output output;
    const char* says;
  };
  using F = gen::Format;
  const BadUse bad[] = {
      {{true, F::R8, nullptr, kChannelG}, "the output channel mask 2 does not fit a r8 output"},
      {{true, F::R16F, nullptr, kChannelR | kChannelA}, "the output channel mask 9 does not fit a r16f output"},
      {{true, F::R16F, nullptr, 0u}, "the output channel mask 0 does not fit a r16f output"},
      {{true, F::RGBA8, nullptr, 0u}, "the output channel mask 0 does not fit a rgba8 output"},
      {{true, F::RGBA8, nullptr, 16u}, "the output channel mask 16 does not fit a rgba8 output"},
      {{true, F::RGBA16F, nullptr, 16u}, "the output channel mask 16 does not fit a rgba16f output"},
      {{false, F::R16F, nullptr, kChannelG}, "the output channel mask 2 does not fit a r16f output"},
      {{false, F::R16F, nullptr, kAllChannels, OutputBlend::Multiply}, "output blend multiply needs your own output"},
      {{false, F::R16F, nullptr, kAllChannels, static_cast<OutputBlend>(7)}, "unknown output blend 7"},
      {{true, F::R16F, nullptr, kAllChannels, static_cast<OutputBlend>(7)}, "unknown output blend 7"},
  };
  const std::string who = api() == Api::Gl     ? "sao::gl: "
                          : api() == Api::Gles ? "sao::gles: "
                                               : "sao::vk::Effect::record() Inputs: ";
  auto e = make();
  for (const BadUse& b : bad) {
    if (b.output.callerOwned && refusesOutput(api(), b.output.format)) continue;
    SCOPED_TRACE(b.says);
    // The caller's output holds texels (a Vulkan image in a defined layout): else Vulkan's record()
    // refuses the undefined layout before it looks at the mask.
    const FloatImage held({cam.width, cam.height}, channelCount(b.output.format));
    Output output = b.output;
    if (output.callerOwned) output.initial = &held;
    const Status st = e->render(frameInto(cam, depth, settingsFor(1), output));
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    EXPECT_NE(st.message.find(who + b.says), std::string::npos) << st.message;
  }
  EXPECT_TRUE(e->render(frameInto(cam, depth, settingsFor(1), {})).ok()) << "the effect stays usable";
}

TEST_P(OutputFormatContract, OutputGenerationFollowsTheOwnedOutput) {
  const Camera small = test::openglCamera(32, 18, 0), large = test::openglCamera(48, 27, 0);
  const DepthImage d1 = test::renderDepth(sceneByName("sphere"), small, DepthFormat::D32F);
  const DepthImage d2 = test::renderDepth(sceneByName("sphere"), large, DepthFormat::D32F);
  auto e = make();
  Settings refused = settingsFor(1);  // GL makes the effect and refuses the frame; Vulkan's create() refuses
  refused.radius = -1;
  EXPECT_FALSE(e->render(frameInto(small, d1, refused, {})).ok());
  EXPECT_EQ(e->outputGeneration(), 0u) << "nothing rendered yet";
  ASSERT_TRUE(e->render(frameInto(small, d1, settingsFor(1), {})).ok());
  const std::uint64_t g1 = e->outputGeneration();
  EXPECT_EQ(g1, 1u);
  ASSERT_TRUE(e->render(frameInto(small, d1, settingsFor(1), {})).ok());
  EXPECT_EQ(e->outputGeneration(), g1) << "a steady frame keeps the output";
  Settings other = settingsFor(1);
  other.intensity = 0.7f;
  ASSERT_TRUE(e->render(frameInto(small, d1, other, {})).ok());
  EXPECT_EQ(e->outputGeneration(), g1) << "new settings, same output";
  ASSERT_TRUE(e->render(frameInto(large, d2, settingsFor(1), {})).ok());
  const std::uint64_t g2 = e->outputGeneration();
  EXPECT_GT(g2, g1) << "a resize makes a new output";
  EXPECT_EQ(e->output().extent, (Extent{48, 27}));
  const Output mine{true, gen::Format::RGBA8};
  ASSERT_TRUE(e->render(frameInto(large, d2, settingsFor(1), mine)).ok());
  const std::uint64_t g3 = e->outputGeneration();
  EXPECT_GT(g3, g2) << "the owned output is released when the caller gives one";
  ASSERT_TRUE(e->render(frameInto(large, d2, settingsFor(1), mine)).ok());
  EXPECT_EQ(e->outputGeneration(), g3) << "the caller's own output never changes it";
  ASSERT_TRUE(e->render(frameInto(large, d2, settingsFor(1), {})).ok());
  const std::uint64_t g4 = e->outputGeneration();
  EXPECT_GT(g4, g3) << "an owned output again";
  EXPECT_FALSE(e->render(frameInto(large, d1, settingsFor(1), {})).ok()) << "depth smaller than the camera";
  EXPECT_EQ(e->outputGeneration(), g4) << "a failed frame changes nothing";
}
SAO_INSTANTIATE_APIS(OutputFormatContract);

}  // namespace
}  // namespace sao::exectest
