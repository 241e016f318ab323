// Vulkan against OpenGL on the same inputs (both on Mesa's LLVM here): the aim is identical output,
// the requirement at most 1/255 anywhere in the final and raw AO (and the reduced (A, key) image at
// a resolution divisor), with the same parameter block. 160x90 + guard 8, the OpenGL camera (60
// degrees, near 0.1, far 1000, [-1,1] depth), the scenes plane(3), crease(2), sphere on a plane,
// stairs, rods: every agreement configuration x D16 / D24 / D32F; the distance fade; the divisors 2
// and 4 at 160x90 and the odd sizes 641x359 and 97x61.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "both_apis.h"
#include "sao/presets.h"
#include "untuned_settings.h"

namespace sao::exectest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;
constexpr double kLimit = 1.0 / 255.0;

// The largest |difference| of one channel (infinite for a shape mismatch or a non-finite value),
// and how many of its values differ in their bits.
struct Diff {
  double max = 0;
  std::size_t differing = 0;
};
Diff diff(const FloatImage& a, const FloatImage& b) {
  Diff d;
  if (a.extent != b.extent || a.channels != b.channels) return {INFINITY, a.data.size()};
  for (std::size_t i = 0; i < a.data.size(); i += a.channels) {
    const float u = a.data[i], v = b.data[i];
    d.differing += std::bit_cast<std::uint32_t>(u) != std::bit_cast<std::uint32_t>(v);
    d.max = std::max(d.max, std::isfinite(u) && std::isfinite(v) ? std::fabs(double(u) - double(v)) : INFINITY);
  }
  return d;
}

// One frame on both APIs: the same parameter block; final AO, raw AO and (with `low`) ao_low's A
// within kLimit everywhere; failure images (Vulkan's as "actual") for an image beyond it.
void expectSameOutput(Executor& gl, Executor& vk, const Frame& f, const std::string& name, bool low = false) {
  for (Executor* e : {&gl, &vk}) {
    const Status st = e->render(f);
    ASSERT_TRUE(st.ok()) << toString(e->api()) << ": " << st.message;
  }
  EXPECT_EQ(std::memcmp(&vk.params(), &gl.params(), sizeof(ParamBlock)), 0) << "same parameter block";
  std::printf("%-34s", name.c_str());
  for (const auto& [label, image] : {std::pair{"final", gen::ResourceId::ao}, std::pair{"raw", gen::ResourceId::ao_raw},
                                     std::pair{"low", gen::ResourceId::ao_low}}) {
    if (image == gen::ResourceId::ao_low && !low) continue;
    const FloatImage v = image == gen::ResourceId::ao ? vk.output() : vk.image(image);
    const FloatImage g = image == gen::ResourceId::ao ? gl.output() : gl.image(image);
    const Diff d = diff(v, g);
    std::printf(" | %s max %.4f/255 (%zu differ)", label, d.max * 255, d.differing);
    EXPECT_LE(d.max, kLimit) << name << " " << label;
    if (d.max > kLimit) (void)compare(Api::Vulkan, v, g, 0, 0.0, kLimit, "vk_gl_" + name + "_" + label);
  }
  std::printf("\n");
}

struct MatrixCase {
  std::size_t settings;  // index into test::agreementSettings()
  Depth format;
};
std::vector<MatrixCase> matrixCases() {
  std::vector<MatrixCase> v;
  for (std::size_t i = 0; i < test::agreementSettings().size(); ++i)
    for (Depth f : {Depth::D16, Depth::D24, Depth::D32F}) v.push_back({i, f});
  return v;
}

using GlEqualsVulkan = BothApis<::testing::TestWithParam<MatrixCase>>;
TEST_P(GlEqualsVulkan, OnEveryScene) {
  Frame f;
  f.settings = test::agreementSettings()[GetParam().settings].settings;
  f.camera = test::openglCamera(kW, kH, kGuard);
  f.format = GetParam().format;
  for (const char* scene : {"plane", "crease", "sphere", "stairs", "rods"}) {
    SCOPED_TRACE(scene);
    const DepthImage depth = test::renderDepth(sceneByName(scene), f.camera, cpuFormat(f.format));
    f.depth = &depth;
    expectSameOutput(*gl, *vk, f,
                     test::agreementSettings()[GetParam().settings].name + "_" + toString(f.format) + "_" + scene);
  }
}
INSTANTIATE_TEST_SUITE_P(Configurations, GlEqualsVulkan, ::testing::ValuesIn(matrixCases()), [](const auto& info) {
  return test::agreementSettings()[info.param.settings].name + "_" + toString(info.param.format);
});

using CrossApi = BothApis<>;

// The distance fade on (3 to 6 m, the floors recede through it).
TEST_F(CrossApi, DistanceFade) {
  Frame f;
  f.settings = presetSettings(Preset::Medium);
  f.settings.fade_start = 3.0f;
  f.settings.fade_end = 6.0f;
  f.camera = test::openglCamera(kW, kH, kGuard);
  for (const char* scene : {"sphere", "stairs"}) {
    SCOPED_TRACE(scene);
    const DepthImage depth = test::renderDepth(sceneByName(scene), f.camera, DepthFormat::D32F);
    f.depth = &depth;
    expectSameOutput(*gl, *vk, f, std::string("fade_3_6_medium_D32F_") + scene);
  }
}

// resolution_divisor 2 and 4 (the medium preset), D24 for the stairs and D32F otherwise.
TEST_F(CrossApi, ReducedResolution) {
  for (const Camera& camera :
       {test::openglCamera(160, 90, 8), test::openglCamera(641, 359, 0), test::openglCamera(97, 61, 3)}) {
    Frame f;
    f.camera = camera;
    for (const char* sceneName : {"plane", "crease", "sphere", "stairs", "rods"}) {
      const std::string scene = sceneName;
      f.format = scene == "stairs" ? Depth::D24 : Depth::D32F;
      const DepthImage depth = test::renderDepth(sceneByName(scene), f.camera, cpuFormat(f.format));
      f.depth = &depth;
      for (int d : {2, 4}) {
        const std::string name = scene + "_" + std::to_string(camera.width) + "x" + std::to_string(camera.height) + "_d" +
                                 std::to_string(d);
        SCOPED_TRACE(name);
        f.settings = presetSettings(Preset::Medium);
        f.settings.resolution_divisor = d;
        expectSameOutput(*gl, *vk, f, name, /*low=*/true);
      }
    }
  }
}

}  // namespace
}  // namespace sao::exectest
