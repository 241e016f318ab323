// The API every engine sees, on each API: bad settings, cameras and input sizes refused with the
// same code, sky, every depth format, resize and reallocation (only the images a change needs are
// made again, no program or pipeline twice, each frame what a fresh effect makes), repeated and
// alternating frames bit-identical, the caller's output, the normals and second-layer variants.
// GL texture names, targets, the loader and timing (tests/gl/effect_test.cpp) and Vulkan layouts,
// record(), frames in flight and timestamps (tests/vulkan/effect_test.cpp) stay with their API.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <map>

#include "harness.h"
#include "msaa_depth.h"
#include "sao/presets.h"
#include "untuned_settings.h"

namespace sao::exectest {
namespace {

using test::sameBits;

// A frame of `scene` through `camera`, owning the depth image it points to.
struct SceneFrame {
  SceneFrame(const test::Scene& scene, const Camera& camera, Depth format = Depth::D32F)
      : depth(test::renderDepth(scene, camera, cpuFormat(format))) {
    frame.camera = camera;
    frame.format = format;
    frame.depth = &depth;
  }
  SceneFrame(const SceneFrame&) = delete;
  SceneFrame& operator=(const SceneFrame&) = delete;
  DepthImage depth;
  Frame frame;
};

// The output of a frame that must render (empty when it did not).
FloatImage renderOutput(Executor& e, const Frame& f) {
  const Status st = e.render(f);
  EXPECT_TRUE(st.ok()) << st.message;
  return st.ok() ? e.output() : FloatImage{};
}

std::size_t countNonFinite(const FloatImage& image) {
  return std::size_t(std::count_if(image.data.begin(), image.data.end(), [](float v) { return !std::isfinite(v); }));
}

// `e`'s last frame, final and raw AO, is bit for bit what a fresh effect makes of `f`.
void expectSameAsFresh(Executor& e, const Frame& f) {
  auto fresh = makeExecutor(e.api());
  ASSERT_TRUE(fresh->render(f).ok());
  EXPECT_EQ(e.plan().cszLevels, fresh->plan().cszLevels);
  EXPECT_TRUE(sameBits(e.output(), fresh->output())) << "final AO differs from a fresh effect's";
  EXPECT_TRUE(sameBits(e.image(gen::ResourceId::ao_raw), fresh->image(gen::ResourceId::ao_raw)))
      << "raw AO differs from a fresh effect's";
}

// `e` refuses `f` with `code` and a message holding each of `needles`.
void expectRefused(Executor& e, const Frame& f, StatusCode code, std::initializer_list<const char*> needles = {}) {
  const Status st = e.render(f);
  EXPECT_EQ(st.code, code) << toString(st.code) << ": " << st.message;
  EXPECT_FALSE(st.message.empty());
  for (const char* needle : needles) EXPECT_NE(st.message.find(needle), std::string::npos) << st.message;
}

using Effect = ApiTest;
TEST_P(Effect, CreatesRendersAndProducesPlausibleObscurance) {
  SceneFrame s(test::sphereOnPlaneScene(), test::vulkanCamera(64, 36, 8));
  auto e = make();
  const FloatImage ao = renderOutput(*e, s.frame);
  ASSERT_EQ(ao.extent, (Extent{64, 36}));
  EXPECT_EQ(e->pipelines(), e->plan().passes.size()) << "one program or pipeline per planned pass variant";
  EXPECT_GE(e->imageAllocations(), 1u);
  EXPECT_EQ(countNonFinite(ao), 0u);
  const auto [lo, hi] = std::minmax_element(ao.data.begin(), ao.data.end());
  EXPECT_GE(*lo, 0.0f);
  EXPECT_LE(*hi, 1.0f);
  EXPECT_LT(*lo, 0.9f) << "the sphere on the floor occludes something";
  EXPECT_GT(*hi, 0.99f) << "the open floor and the sky stay unoccluded";
  std::printf("%s plan: %s", toString(api()), e->plan().describe().c_str());
}

// Every depth format; those holding the same texels (D24 and D24S8, D32F and D32FS8) agree bit for bit.
TEST_P(Effect, EveryDepthFormat) {
  std::map<DepthFormat, FloatImage> first;
  for (Depth format : {Depth::D16, Depth::D24, Depth::D24S8, Depth::D32F, Depth::D32FS8, Depth::R32F}) {
    SCOPED_TRACE(toString(format));
    SceneFrame s(test::stairsScene(), test::vulkanCamera(48, 27, 8), format);
    const FloatImage ao = renderOutput(*make(), s.frame);
    const auto [it, inserted] = first.emplace(cpuFormat(format), ao);
    if (!inserted) {
      EXPECT_TRUE(sameBits(ao, it->second)) << "same texels, another format";
    }
  }
}

// The same frame three times, and two inputs alternating: each frame reads its own depth and
// gives what it gave the first time, bit for bit.
TEST_P(Effect, RepeatedFramesAreBitIdentical) {
  SceneFrame rods(test::rodsScene(), test::vulkanCamera(48, 27, 8));
  auto e = make();
  const FloatImage once = renderOutput(*e, rods.frame);
  for (int frame = 0; frame < 2; ++frame) EXPECT_TRUE(sameBits(renderOutput(*e, rods.frame), once)) << frame;
}

TEST_P(Effect, AlternatingInputsReadTheirOwnDepth) {
  SceneFrame sphere(test::sphereOnPlaneScene(), test::vulkanCamera(48, 27, 8));
  SceneFrame stairs(test::stairsScene(), test::vulkanCamera(48, 27, 8));
  auto e = make();
  const FloatImage first = renderOutput(*e, sphere.frame), second = renderOutput(*e, stairs.frame);
  EXPECT_FALSE(sameBits(first, second));
  for (int round = 0; round < 3; ++round) {
    EXPECT_TRUE(sameBits(renderOutput(*e, sphere.frame), first)) << "round " << round;
    EXPECT_TRUE(sameBits(renderOutput(*e, stairs.frame), second)) << "round " << round;
  }
}

TEST_P(Effect, NormalsAndSecondLayerVariantsRun) {
  const test::Scene scene = test::sphereOnPlaneScene();
  SceneFrame s(scene, test::vulkanCamera(48, 27, 8));
  const DepthImage depth2 = test::renderDepth(scene, s.frame.camera, DepthFormat::D32F, 1);
  const FloatImage normals = test::renderNormals(scene, s.frame.camera);
  auto e = make();
  const FloatImage plain = renderOutput(*e, s.frame);
  Frame f = s.frame;
  f.normals = &normals;
  const FloatImage withNormals = renderOutput(*e, f);
  EXPECT_EQ(e->plan().variants[std::size_t(gen::VariantId::NORMALS_SUPPLIED)], 1);
  f = s.frame;
  f.depth2 = &depth2;
  renderOutput(*e, f);
  EXPECT_EQ(e->plan().variants[std::size_t(gen::VariantId::TWO_LAYER)], 1);
  // Analytic normals and rebuilt ones give nearly the same obscurance on this smooth scene.
  const Agreement a = compare(api(), withNormals, plain, 0, 0.05, 1.0, "normals_vs_rebuilt");
  EXPECT_GT(a.fractionWithin, 0.9);
}
SAO_INSTANTIATE_APIS(Effect);

// ---- Bad frames: the same code on each API (GL: render(); Vulkan: record()), with a message;
// the effect then renders.
using Inputs = ApiTest;
TEST_P(Inputs, BadSettingsAndCamera) {
  SceneFrame s(test::sphereOnPlaneScene(), test::openglCamera(64, 36, 8), Depth::D24);
  auto e = make();
  Frame f = s.frame;
  f.settings.samples = 0;
  expectRefused(*e, f, StatusCode::InvalidSetting);
  f.settings = {};
  f.settings.radius = -1.0f;
  expectRefused(*e, f, StatusCode::InvalidSetting);
  f.settings = {};
  f.camera.projection[11] = 0.0;  // not a perspective projection any more
  expectRefused(*e, f, StatusCode::InvalidCamera);
  f.camera.projection[11] = 0.5;  // not a projection of the declared kind
  expectRefused(*e, f, StatusCode::InvalidCamera);
  f.camera = s.frame.camera;
  f.camera.width = 0;  // the core's camera analysis rejects an empty viewport first
  expectRefused(*e, f, StatusCode::InvalidCamera);
  f.camera = test::vulkanCamera(20000, 100, 0);  // beyond kMaxImageSide and the device's limit
  expectRefused(*e, f, StatusCode::InvalidExtent);
  EXPECT_TRUE(e->render(s.frame).ok());
}

TEST_P(Inputs, DepthSizeMustBeViewportPlusGuard) {
  SceneFrame s(test::sphereOnPlaneScene(), test::openglCamera(64, 36, 8), Depth::D24);  // 80x52
  auto e = make();
  Frame f = s.frame;
  f.camera.guardBand = 0;  // the image holds a guard band the camera does not declare
  expectRefused(*e, f, StatusCode::InvalidInput, {"80x52", "64x36", "set Inputs::region"});
  f.camera.guardBand = 9;  // needs 82x54: too large for the image, with or without a region
  expectRefused(*e, f, StatusCode::InvalidInput, {"82x54"});
  SceneFrame viewportOnly(test::sphereOnPlaneScene(), test::openglCamera(64, 36, 0), Depth::D24);
  f = viewportOnly.frame;
  f.camera.guardBand = 8;  // the viewport's depth, without the guard band the camera declares
  expectRefused(*e, f, StatusCode::InvalidInput, {"64x36", "80x52"});
  EXPECT_TRUE(e->render(s.frame).ok());
}

TEST_P(Inputs, NormalsOfAnotherSizeAreRefused) {
  SceneFrame s(test::sphereOnPlaneScene(), test::openglCamera(64, 36, 8), Depth::D24);
  const FloatImage viewportOnly(Extent{64, 36}, 4);  // the depth is 80x52
  auto e = make();
  Frame f = s.frame;
  f.normals = &viewportOnly;
  expectRefused(*e, f, StatusCode::InvalidInput);
  EXPECT_TRUE(e->render(s.frame).ok());
}
SAO_INSTANTIATE_APIS(Inputs);

// ---- Sky: depth = far everywhere gives A = 1, the key +0.0 and no NaN / Inf in any image, with
// the defaults and every preset, in each depth representation, both clip ranges, finite and
// infinite far, standard and reversed Z.
struct SkyCase {
  Depth format;
  bool infinite, reversed, zeroToOne;
};
std::string caseName(const SkyCase& c) {
  return std::string(toString(c.format)) + (c.infinite ? "_infinite" : "_finite") + (c.reversed ? "_reversed" : "") +
         (c.zeroToOne ? "_zero_to_one" : "");
}
const SkyCase kSkyCases[] = {
    {Depth::D24, true, false, false},  {Depth::D32F, true, false, false}, {Depth::D16, true, false, false},
    {Depth::D32F, true, true, false},  {Depth::D24S8, false, false, false}, {Depth::R32F, true, false, false},
    {Depth::D32F, false, false, true}, {Depth::D32F, true, true, true},
};

using Sky = ApiCaseTest<SkyCase>;
TEST_P(Sky, IsUnoccludedAndFinite) {
  const SkyCase& c = param();
  const double far = c.infinite ? INFINITY : 100.0;
  const Camera camera =
      c.zeroToOne ? test::vulkanCamera(160, 90, 8, far, c.reversed) : test::openglCamera(160, 90, 8, far, c.reversed);
  SceneFrame s(test::skyScene(), camera, c.format);
  std::vector<std::pair<std::string, Settings>> settings = {{"defaults", Settings{}}};
  for (const auto& preset : presets()) settings.emplace_back(preset.name, presetSettings(preset.preset));
  auto e = make();
  for (const auto& [name, values] : settings) {
    SCOPED_TRACE(name);
    s.frame.settings = values;
    const FloatImage ao = renderOutput(*e, s.frame), raw = e->image(gen::ResourceId::ao_raw);
    ASSERT_FALSE(raw.data.empty());
    EXPECT_EQ(countNonFinite(ao), 0u);
    EXPECT_EQ(countNonFinite(raw), 0u);
    for (float a : ao.data) ASSERT_EQ(a, 1.0f);
    for (std::size_t i = 0; i + 1 < raw.data.size(); i += 2) {
      ASSERT_EQ(raw.data[i], 1.0f);
      ASSERT_EQ(std::bit_cast<std::uint32_t>(raw.data[i + 1]), 0u) << "the key of sky is +0.0";
    }
    EXPECT_EQ(countNonFinite(e->image(gen::ResourceId::ao_low)), 0u);
    for (std::uint32_t m = 0; m < e->plan().cszLevels; ++m) {
      const FloatImage z = e->image(gen::ResourceId::csz, m);
      ASSERT_FALSE(z.data.empty()) << "csz level " << m;
      for (float v : z.data) ASSERT_EQ(std::bit_cast<std::uint32_t>(v), 0u) << "csz level " << m << " is +0.0 (sky)";
    }
  }
}
SAO_INSTANTIATE_API_CASES(Sky, kSkyCases);

// ---- Resize: 640x360 -> 1281x721 -> 640x360 equals a fresh effect at each size.
using Resize = ApiTest;
TEST_P(Resize, MatchesAFreshEffectAtEachSize) {
  auto reused = make();
  for (const auto& [w, h] : {std::pair{640u, 360u}, std::pair{1281u, 721u}, std::pair{640u, 360u}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    SceneFrame s(test::sphereOnPlaneScene(), test::openglCamera(w, h, 8), Depth::D24);
    s.frame.settings = presetSettings(Preset::Medium);
    const FloatImage a = renderOutput(*reused, s.frame);
    EXPECT_EQ(reused->plan().aoExtent, (Extent{w, h}));
    EXPECT_EQ(a.extent, (Extent{w, h}));
    expectSameAsFresh(*reused, s.frame);
    double mean = 0;
    for (float v : a.data) mean += v;
    mean /= double(a.data.size());
    EXPECT_LT(mean, 0.999) << "the scene should show some obscurance";
    EXPECT_GT(mean, 0.5);
  }
}
SAO_INSTANTIATE_APIS(Resize);

// ---- Reallocation follows the plan: a change makes again only the images it changes and builds
// only the programs or pipelines of pass variants not built yet; every frame is what a fresh
// effect makes, and a refused frame keeps the configuration.
// Image storage made for `images` new images: a texture each on GL, one memory block for them all
// on Vulkan (they share a memory type), a memory block each in the engine-side example.
std::uint64_t storageFor(Api api, std::uint64_t images) { return api == Api::Vulkan ? images > 0 : images; }

using Reallocation = ApiTest;
TEST_P(Reallocation, OnlyWhatChanged) {
  SceneFrame small(test::sphereOnPlaneScene(), test::openglCamera(160, 90, 8));
  Frame& f = small.frame;
  f.settings = test::untunedDefaults();  // full resolution with a blur: csz, ao_raw, ao_low, ao
  auto e = make();
  ASSERT_TRUE(e->render(f).ok());
  std::uint64_t allocations = e->imageAllocations(), pipelines = e->pipelines();
  EXPECT_EQ(allocations, storageFor(api(), 4));
  EXPECT_EQ(pipelines, e->plan().passes.size());
  const std::uint32_t levels = e->plan().cszLevels;
  const auto step = [&](const char* what, std::uint64_t newImages, std::uint64_t newVariants) {
    SCOPED_TRACE(what);
    const Status st = e->render(f);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(e->imageAllocations(), allocations += storageFor(api(), newImages));
    EXPECT_EQ(e->pipelines(), pipelines += newVariants);
    expectSameAsFresh(*e, f);
  };
  f.settings.intensity = 2.0f;
  f.settings.samples = 20;
  f.settings.blur_radius = 6;
  step("parameters only", 0, 0);
  f.settings.blur_radius = 0;
  step("nothing follows the AO: ao_sample_output, ao_raw and ao_low freed", 0, 1);
  EXPECT_EQ(e->plan().passes.size(), 2u) << "linear_z, ao_sample_output";
  EXPECT_EQ(e->plan().image(gen::ResourceId::ao_raw), nullptr);
  EXPECT_EQ(e->plan().image(gen::ResourceId::ao_low), nullptr);
  f.settings.blur_radius = 4;
  step("the blur back: ao_raw and ao_low made again", 2, 0);
  f.settings.radius = 0.05f;
  step("fewer csz levels: only csz made again", 1, 0);
  EXPECT_LT(e->plan().cszLevels, levels);
  f.settings.use_z_hierarchy = false;
  step("one csz level: csz again, another ao_sample variant", 1, 1);
  EXPECT_EQ(e->plan().cszLevels, 1u);
  SceneFrame large(test::sphereOnPlaneScene(), test::openglCamera(200, 112, 8));
  large.frame.settings = f.settings;
  f = large.frame;
  step("a resize: every image made again", 4, 0);
  EXPECT_EQ(e->output().extent, (Extent{200, 112}));
  Frame bad = f;
  bad.settings.samples = 0;
  expectRefused(*e, bad, StatusCode::InvalidSetting);
  EXPECT_EQ(e->output().extent, (Extent{200, 112})) << "a refused frame keeps the configuration";
  step("the frame before the refused one", 0, 0);
}
SAO_INSTANTIATE_APIS(Reallocation);

// ---- The caller's output (R16F) receives what the effect's own output holds, on an effect that
// switches to it and on one that starts with it, every frame; no owned output is planned then.
using Output = ApiTest;
TEST_P(Output, CallersOutputReceivesTheSameImage) {
  SceneFrame s(test::stairsScene(), test::openglCamera(160, 90, 8), Depth::D24);
  auto switching = make(), starting = make();
  const FloatImage owned = renderOutput(*switching, s.frame);
  EXPECT_NE(switching->plan().image(gen::ResourceId::ao), nullptr);
  Frame mine = s.frame;
  mine.output.callerOwned = true;
  for (Executor* e : {switching.get(), starting.get()})
    for (int frame = 0; frame < 2; ++frame) {
      EXPECT_TRUE(sameBits(renderOutput(*e, mine), owned)) << "frame " << frame;
      EXPECT_EQ(e->plan().image(gen::ResourceId::ao), nullptr) << "no owned output when the caller gives one";
    }
}
SAO_INSTANTIATE_APIS(Output);

// ---- What harness.h's Feature names: on an executor that lacks some (the engine-side example; GLES
// a multisampled depth and stereo), a frame needing one it lacks is refused by name (InvalidInput)
// and the effect renders afterwards; one it has renders. GL and Vulkan have every feature, each run
// by its own program (output_format, msaa_depth, stereo): the test runs on the others only.
// (Feature::LibraryAllocations is no frame's: the tests counting allocations skip.)
std::vector<Api> lackingAFeature() {
  std::vector<Api> v;
  for (Api a : apis())
    for (Feature f : {Feature::OutputContents, Feature::MultisampledDepth, Feature::Stereo})
      if (!supports(a, f)) {
        v.push_back(a);
        break;
      }
  return v;
}

using Features = ApiTest;
TEST_P(Features, RenderWhereImplementedAndAreRefusedByNameElsewhere) {
  SceneFrame s(test::sphereOnPlaneScene(), test::vulkanCamera(64, 36, 8));
  const FloatImage half(Extent{64, 36}, 1, 0.5f);
  const DepthImage fourSamples = test::interleaveSamples({&s.depth}, 4);
  Frame multiply = s.frame, msaa = s.frame, stereo = s.frame;
  multiply.output = {true, gen::Format::R16F, &half, kAllChannels, OutputBlend::Multiply};
  msaa.depth = &fourSamples;
  stereo.depth = nullptr;
  stereo.depthLayers = {&s.depth, &s.depth};
  stereo.output.callerOwned = true;
  auto e = make();
  for (const auto& [feature, frame] : {std::pair<Feature, const Frame&>{Feature::OutputContents, multiply},
                                       std::pair<Feature, const Frame&>{Feature::MultisampledDepth, msaa},
                                       std::pair<Feature, const Frame&>{Feature::Stereo, stereo}}) {
    SCOPED_TRACE(describe(feature));
    const Status st = e->render(frame);
    if (supports(api(), feature)) {
      EXPECT_TRUE(st.ok()) << st.message;
      continue;
    }
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    EXPECT_NE(st.message.find(describe(feature)), std::string::npos) << st.message;
  }
  EXPECT_TRUE(e->render(s.frame).ok());
}
INSTANTIATE_TEST_SUITE_P(Apis, Features, ::testing::ValuesIn(lackingAFeature()), apiName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Features);  // a build without the engine-side example

}  // namespace
}  // namespace sao::exectest
