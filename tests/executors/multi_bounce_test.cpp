// The multi-bounce term (setting albedo) on each API against the CPU reference (Float): the five
// analytic scenes x every agreement configuration (each preset, the z hierarchy off, the untuned
// defaults, and no blur at full resolution, where ao_sample_output stores the output) at albedo
// 0.6, under GL's usual conventions (D24, [-1, 1], the plane 3 m away) and Vulkan's (D32F, [0, 1],
// 2 m), to the reference tests' bounds (99.9 % within 2/255, none beyond 4/255). The raw
// (pre-output) AO does not see the albedo: it agrees with the CPU's single-bounce raw AO too.
// Every output format, mask and blend at albedo 0.6: output_format_test.cpp.
#include "harness.h"
#include "sao/presets.h"
#include "untuned_settings.h"

namespace sao::exectest {
namespace {

constexpr float kAlbedo = 0.6f;

std::vector<test::NamedSettings> configurations() {
  std::vector<test::NamedSettings> v = test::agreementSettings();
  Settings direct = presetSettings(Preset::Reference);
  direct.blur_radius = 0;  // with resolution_divisor 1: ao_sample_output writes the output
  v.push_back({"direct", direct});
  return v;
}

struct Conventions {
  std::string name;
  Camera camera;
  Depth format;
  double planeDistance;
};
std::string caseName(const Conventions& s) { return s.name; }
void PrintTo(const Conventions& s, std::ostream* os) { *os << s.name; }
const Conventions kConventions[] = {{"opengl_D24", test::openglCamera(160, 90, 8), Depth::D24, 3.0},
                         {"vulkan_D32F", test::vulkanCamera(160, 90, 8, 100.0), Depth::D32F, 2.0}};

using MultiBounce = ApiCaseTest<Conventions>;
TEST_P(MultiBounce, AgreesWithTheCpuReferenceOnEveryScene) {
  const Conventions& s = param();
  auto e = make();
  for (const test::Scene& scene : {test::planeScene(s.planeDistance), test::creaseScene(2.0), test::sphereOnPlaneScene(),
                                   test::stairsScene(), test::rodsScene()}) {
    const DepthImage depth = test::renderDepth(scene, s.camera, cpuFormat(s.format));
    for (const auto& [label, base] : configurations()) {
      const std::string name = "bounce_" + s.name + "_" + scene.name + "_" + label;
      SCOPED_TRACE(name);
      Frame f;
      f.settings = base;
      f.settings.albedo = kAlbedo;
      f.camera = s.camera;
      f.depth = &depth;
      f.format = s.format;
      const Status st = e->render(f);
      ASSERT_TRUE(st.ok()) << st.message;
      cpu::Result ref, single;
      ASSERT_TRUE(runCpu(f, ref).ok());
      EXPECT_EQ(ref.params.multi_bounce, 1);
      expectAgreesWithCpu(*e, ref, name);
      f.settings.albedo = 0;
      ASSERT_TRUE(runCpu(f, single).ok());
      if (single.aoRaw.data.empty()) continue;  // "direct": there is no ao_raw
      const Agreement r = compare(api(), e->image(gen::ResourceId::ao_raw), single.aoRaw, 0, kWithin, kNever,
                                  name + "_raw_single");
      EXPECT_TRUE(acceptable(r)) << "raw AO against the single-bounce raw AO: max |diff| " << r.maxAbs * 255 << "/255";
    }
  }
}
SAO_INSTANTIATE_API_CASES(MultiBounce, kConventions);

}  // namespace
}  // namespace sao::exectest
