// The test harness over executors: the effect on each graphics API driven as an engine drives it,
// one call per frame with settings, camera and inputs, the inputs uploaded from host images and
// the results read back as floats. The shared suite (tests/executors/*_test.cpp) runs every case
// on every API through it; what only one API has (GL state restore, Vulkan layouts, frames in
// flight, synchronisation) stays in tests/gl and tests/vulkan.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "analytic_scenes.h"
#include "image_compare.h"
#include "sao/cpu/reference.h"
#include "sao/camera.h"
#include "sao/image.h"
#include "sao/output.h"
#include "sao/plan.h"
#include "sao/settings.h"
#include "test_cameras.h"

namespace sao::exectest {

// Gl and Vulkan: the library's backends. Engine: the engine-side example (samples/integration/
// vk_engine: sao::core's FrameState driving an engine's own executor on raw Vulkan, shaders from
// the build's .spv files) on the Vulkan test context. Gles: sao::gles (the OpenGL backend's sources
// built for OpenGL ES 3.1) on a headless ES context of its own. A program runs the engine and GLES
// where it is declared ENGINE and GLES (tests/executors/CMakeLists.txt).
enum class Api { Gl, Vulkan, Engine, Gles };
const char* toString(Api api);  // "gl", "vulkan", "engine", "gles"
inline void PrintTo(Api api, std::ostream* os) { *os << toString(api); }
std::vector<Api> apis();  // the APIs this test program runs (program_apis.cpp)

// What a case may need that not every executor implements. GL and Vulkan implement all of them;
// the engine-side example none; GLES all but MultisampledDepth and Stereo (sao::gles refuses them).
// An executor refuses a frame that needs one it lacks (InvalidInput, naming it). A case that needs
// one starts with SAO_SKIP_UNLESS_SUPPORTED.
enum class Feature {
  OutputContents,     // an output whose texels the frame keeps: Output::initial, a channel mask, a blend
  MultisampledDepth,  // a depth of DepthImage::samples > 1
  Stereo,             // Frame::depthLayers
  // The per-frame call's heap allocations counted in a shared library of the API's own
  // (api_allocations.h): the engine is linked into the test program, and allocates per frame.
  LibraryAllocations,
};
const char* describe(Feature feature);
bool supports(Api api, Feature feature);
// Whether `api` refuses a caller's output of `format` (UnsupportedFormat): GLES those without an ES
// form (gen::glesRefuses: R8); every other API none.
bool refusesOutput(Api api, gen::Format format);
// Skips the running test, naming the executor and what it lacks, where `api` does not support `feature`.
#define SAO_SKIP_UNLESS_SUPPORTED(api, feature)                                                           \
  if (::sao::exectest::supports(api, feature)) {                                                          \
  } else /* the else binds here, whatever surrounds the macro */                                          \
    GTEST_SKIP() << ::sao::exectest::toString(api) << " does not implement " << ::sao::exectest::describe(feature)

// The depth representations both APIs take (GL D24 is Vulkan's X8_D24_UNORM_PACK32).
enum class Depth { D16, D24, D24S8, D32F, D32FS8, R32F };
const char* toString(Depth format);
DepthFormat cpuFormat(Depth format);  // the DepthImage format holding the same texels

// How a colour input (normals, motion) is stored: 16-bit floats are rounded to nearest-even on the host.
enum class Texels { RGBA16F, RGBA32F, RG16F, RG32F };

// The output: the effect's own (R16F unless `format` says otherwise) or the caller's image,
// holding `initial` (the format's channels) before the frame when given. GLES stores it in the
// format's ES form (gen::glesStorageFormat: R16F as R32F); sao::gles refuses R8 (refusesOutput).
struct Output {
  bool callerOwned = false;
  gen::Format format = gen::Format::R16F;
  const FloatImage* initial = nullptr;
  std::uint32_t channels = kAllChannels;
  OutputBlend blend = OutputBlend::Replace;
};

// One frame: what an engine hands the per-frame call. Images are host images, uploaded by upload().
struct Frame {
  Settings settings;
  Camera camera;
  // May be multisampled (DepthImage::samples 4, D32F; tests/cpu/msaa_depth.h), each sample written
  // by the API's writer: GL a GL_TEXTURE_2D_MULTISAMPLE, Vulkan an image of that many samples (InputImage::samples).
  const DepthImage* depth = nullptr;
  Depth format = Depth::D32F;
  bool depthReadOnlyLayout = false;  // Vulkan: depth in DEPTH_STENCIL_READ_ONLY_OPTIMAL, not SHADER_READ_ONLY
  const DepthImage* depth2 = nullptr;
  const FloatImage* normals = nullptr;
  Texels normalsTexels = Texels::RGBA16F;
  const FloatImage* motion = nullptr;
  Texels motionTexels = Texels::RG16F;
  std::optional<Offset> region;  // the inputs are larger images holding the region from here
  Output output;
  std::uint32_t frameIndex = 0;
  bool resetHistory = false;
  const Camera* previousCamera = nullptr;
  // Stereo: one host depth per array layer in place of `depth` (single-sample D32F, one extent): the
  // depth and the caller's output (output.callerOwned, no initial contents; nothing else) become
  // arrays of as many layers, made once by upload(); each run renders layer `layer` with `camera`
  // (GL Inputs::layer; Vulkan a 2D view per layer, OutputImage::layer) and output() reads it.
  std::vector<const DepthImage*> depthLayers;
  std::uint32_t layer = 0;
};

// The effect on one API. Every call needs the API's test context (the fixture below makes it).
class Executor {
 public:
  virtual ~Executor() = default;
  virtual Api api() const = 0;
  // upload() then run(): the usual frame.
  Status render(const Frame& frame);
  // The frame's images onto the device (the previous upload's are released).
  virtual Status upload(const Frame& frame) = 0;
  // The per-frame call on what upload() made (images are taken from there, everything else from
  // `frame`), then waits for the device. GL: render(); Vulkan: record(cmd, camera, settings,
  // inputs), submitted (a new effect only for what Config alone says: the depth's sample count, the
  // effect-owned output's format); Engine: EngineEffect::run(settings, camera, frame) (the caller's
  // output: the engine's own image, EngineFrame::engineOutput).
  virtual Status run(const Frame& frame) = 0;
  // The output after the last successful run, in its format's channels.
  virtual FloatImage output() = 0;
  // An effect-owned image of the last plan, level `level` (its format's channels); empty if not planned.
  virtual FloatImage image(gen::ResourceId resource, std::uint32_t level = 0) = 0;
  virtual const Plan& plan() const = 0;
  virtual const ParamBlock& params() const = 0;
  // Counters: configurations planned (GL: Stats::plans; Vulkan: plans(); Engine: FrameState's),
  // image storage made so far (GL: textures; Vulkan: device memory blocks, the parameter buffer's
  // not counted; Engine: images, one block each, its output's included), programs or pipelines built.
  virtual std::uint64_t plans() const = 0;
  virtual std::uint64_t imageAllocations() const = 0;
  virtual std::uint64_t pipelines() const = 0;
  virtual std::uint64_t outputGeneration() const = 0;
  // Frees the effect (the next run creates it again); uploaded inputs stay.
  virtual void releaseEffect() = 0;
};

// A fresh executor for `api` (its context made on first use).
std::unique_ptr<Executor> makeExecutor(Api api);

// Every test fails on a GL or GLES debug error or a Vulkan validation message raised while it ran
// (the engine's included: it runs on the Vulkan context).
class ApiTest : public ::testing::TestWithParam<Api> {
 protected:
  void SetUp() override;
  void TearDown() override;
  Api api() const { return GetParam(); }
  std::unique_ptr<Executor> make() { return makeExecutor(GetParam()); }
};

// A parameterised test over (Api, Case): GetParam() is a tuple.
template <typename Case>
class ApiCaseTest : public ::testing::TestWithParam<std::tuple<Api, Case>> {
 protected:
  void SetUp() override;
  void TearDown() override;
  Api api() const { return std::get<0>(this->GetParam()); }
  const Case& param() const { return std::get<1>(this->GetParam()); }
  std::unique_ptr<Executor> make() { return makeExecutor(api()); }
};
void checkMessagesBefore(Api api);  // the fixtures' SetUp and TearDown
void checkMessagesAfter(Api api);
template <typename Case>
void ApiCaseTest<Case>::SetUp() { checkMessagesBefore(api()); }
template <typename Case>
void ApiCaseTest<Case>::TearDown() { checkMessagesAfter(api()); }

// Test names: "gl", "vulkan", "engine", "gles"; with a case, "<api>_<case name>" from caseName(const Case&).
std::string apiName(const ::testing::TestParamInfo<Api>& info);
#define SAO_INSTANTIATE_APIS(Suite) \
  INSTANTIATE_TEST_SUITE_P(Apis, Suite, ::testing::ValuesIn(::sao::exectest::apis()), ::sao::exectest::apiName)
#define SAO_INSTANTIATE_API_CASES(Suite, cases)                                                            \
  INSTANTIATE_TEST_SUITE_P(Apis, Suite, ::testing::Combine(::testing::ValuesIn(::sao::exectest::apis()), \
                                                           ::testing::ValuesIn(cases)),                  \
                           [](const auto& info) {                                                          \
                             return std::string(::sao::exectest::toString(std::get<0>(info.param))) + "_" + \
                                    caseName(std::get<1>(info.param));                                     \
                           })

// The scenes of the agreement tests: "plane" (3 m away), "crease" (2 m), "sphere" (on a plane),
// "stairs", anything else the rods.
test::Scene sceneByName(const std::string& name);

// test::compare with the failure images under tests/executors/failures/<api> in the build tree.
using test::acceptable;
using test::Agreement;
Agreement compare(Api api, const FloatImage& actual, const FloatImage& expected, std::uint32_t channel, double within,
                  double never, const std::string& name, std::string* note = nullptr);

// The CPU reference (float, 2 threads) on the frame's host images: its output format, channels,
// blend and initial contents, frame index, region, motion and `history` (the previous run's
// Result::images[history][0], with frame.previousCamera) as the GPU run gets them.
Status runCpu(const Frame& frame, cpu::Result& out, const FloatImage* history = nullptr);

// The agreement bounds with the CPU reference: 99.9 % of the pixels within 2/255, none beyond 4/255.
inline constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;
// Compares the executor's last run with `reference`: the final AO (channel 0) and the raw AO
// within the bounds, the parameter blocks byte for byte, the raw keys (camera-space z) within 1e-5
// relative; prints one AGREEMENT line; `name` names the failure images. Returns the two figures.
struct CpuAgreement {
  Agreement final, raw;
};
CpuAgreement expectAgreesWithCpu(Executor& executor, const cpu::Result& reference, const std::string& name);

}  // namespace sao::exectest
