// resolution_divisor 2 and 4 against the CPU reference (float): the final AO, the reduced raw AO
// and the reduced (A, key) image the upsample reads, at the agreement bounds, at 160x90 with a
// guard band and at the odd sizes 641x359 and 97x61, under OpenGL's depth convention and under a
// reversed infinite [0,1] one; back to divisor 1 after a reduced frame; and no seam at the odd
// sizes (seam_metric.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "harness.h"
#include "sao/presets.h"
#include "seam_metric.h"

namespace sao::exectest {
namespace {

Settings reduced(int divisor) {
  Settings s = presetSettings(Preset::Medium);
  s.resolution_divisor = divisor;
  return s;
}

// A size under OpenGL's depth convention or a reversed infinite [0,1] one (each former API test's
// camera, with its plane distance).
struct SizeCase {
  std::uint32_t width, height, guard;
  bool reversedInfinite;
};
std::string caseName(const SizeCase& c) {
  return std::to_string(c.width) + "x" + std::to_string(c.height) + (c.reversedInfinite ? "_reversed_infinite" : "_opengl");
}
std::vector<SizeCase> sizeCases() {
  std::vector<SizeCase> v;
  for (bool r : {false, true})
    for (const SizeCase c : {SizeCase{160, 90, 8, r}, SizeCase{641, 359, 0, r}, SizeCase{97, 61, 3, r}}) v.push_back(c);
  return v;
}

using ReducedResolution = ApiCaseTest<SizeCase>;
TEST_P(ReducedResolution, MatchesTheCpuReference) {
  const SizeCase& sc = param();
  const Camera cam = sc.reversedInfinite ? test::vulkanCamera(sc.width, sc.height, sc.guard, INFINITY, true)
                                         : test::openglCamera(sc.width, sc.height, sc.guard);
  auto e = make();
  for (const char* sceneName : {"plane", "crease", "sphere", "stairs", "rods"}) {
    const std::string scene = sceneName;
    if (sc.width > 200 && scene == "plane") continue;  // NoSeamAtOddSizes runs it
    Frame f;
    f.camera = cam;
    f.format = scene == "stairs" ? Depth::D24 : Depth::D32F;
    const DepthImage depth = test::renderDepth(
        scene == "plane" ? test::planeScene(sc.reversedInfinite ? 2.0 : 3.0) : sceneByName(scene), cam, cpuFormat(f.format));
    f.depth = &depth;
    for (int d : {2, 4}) {
      const std::string name = scene + "_" + caseName(sc) + "_d" + std::to_string(d);
      SCOPED_TRACE(name);
      f.settings = reduced(d);
      const Status st = e->render(f);
      ASSERT_TRUE(st.ok()) << st.message;
      cpu::Result ref;
      ASSERT_TRUE(runCpu(f, ref).ok());
      EXPECT_EQ(e->plan().describe(), ref.plan.describe());
      expectAgreesWithCpu(*e, ref, name);
      // The reduced (A, key) image: A within the bounds, the keys csz texels copied bit for bit.
      const FloatImage low = e->image(gen::ResourceId::ao_low);
      const FloatImage& refLow = ref.images[std::size_t(gen::ResourceId::ao_low)].at(0);
      const Agreement l = compare(api(), low, refLow, 0, kWithin, kNever, name + "_low");
      const Agreement k = compare(api(), low, refLow, 1, 0.0, 0.0, name + "_low_key");
      EXPECT_TRUE(acceptable(l)) << "low: max " << l.maxAbs * 255 << "/255, " << l.beyond << " beyond 4/255";
      EXPECT_EQ(k.maxAbs, 0.0) << "the low keys are csz texels, copied";
    }
  }
}
SAO_INSTANTIATE_API_CASES(ReducedResolution, sizeCases());

using ReducedResolutionApi = ApiTest;
// Divisor 1 after a reduced frame: the effect goes back to the full-resolution plan and output.
TEST_P(ReducedResolutionApi, BackToFullResolution) {
  Frame f;
  f.camera = test::openglCamera(160, 90, 8);
  const DepthImage depth = test::renderDepth(sceneByName("sphere"), f.camera, DepthFormat::D32F);
  f.depth = &depth;
  auto e = make();
  f.settings = reduced(4);
  ASSERT_TRUE(e->render(f).ok());
  f.settings = reduced(1);
  ASSERT_TRUE(e->render(f).ok());
  cpu::Result ref;
  ASSERT_TRUE(runCpu(f, ref).ok());
  const PlannedImage* low = e->plan().image(gen::ResourceId::ao_low);
  ASSERT_NE(low, nullptr) << "the blur's image";
  EXPECT_EQ(low->extent, (Extent{160, 90})) << "full resolution: ao_low is the viewport's size";
  const Agreement a = compare(api(), e->output(), ref.ao, 0, kWithin, kNever, "back_to_full");
  EXPECT_TRUE(acceptable(a)) << "max " << a.maxAbs * 255 << "/255";
}

// No row or column of the output stands out at odd sizes: an open plane is 1 everywhere, the
// creases' row (vertical crease) and column (horizontal crease) means are flat (seam_metric.h).
TEST_P(ReducedResolutionApi, NoSeamAtOddSizes) {
  auto e = make();
  const auto ao = [&](const Camera& cam, const test::Scene& scene, int d) {
    const DepthImage depth = test::renderDepth(scene, cam, DepthFormat::D32F);
    Frame f;
    f.settings = reduced(d);
    f.camera = cam;
    f.depth = &depth;
    const Status st = e->render(f);
    EXPECT_TRUE(st.ok()) << st.message;
    return st.ok() ? e->output() : FloatImage{};
  };
  for (const Camera& cam : {test::openglCamera(641, 359, 0), test::openglCamera(97, 61, 0),
                            test::vulkanCamera(641, 359, 0, 100.0), test::vulkanCamera(97, 61, 0, 100.0)}) {
    for (int d : {2, 4}) {
      const std::string where = std::to_string(cam.width) + (cam.clipDepth == ClipDepth::ZeroToOne ? " [0,1]" : " [-1,1]") +
                                " d=" + std::to_string(d);
      SCOPED_TRACE(where);
      const FloatImage p = ao(cam, test::planeScene(3.0), d);
      ASSERT_FALSE(p.data.empty());
      EXPECT_EQ(*std::min_element(p.data.begin(), p.data.end()), 1.0f);
      const test::SeamScore rows = test::seamScore(ao(cam, test::creaseScene(2.0), d), /*margin=*/2 * d);
      const test::SeamScore cols = test::seamScore(ao(cam, test::horizontalCreaseScene(2.0), d), /*margin=*/2 * d);
      std::printf("%s seam %s: rows %.4f/255 (row %u), columns %.4f/255 (column %u)\n", toString(api()), where.c_str(),
                  rows.row * 255, rows.worstRow, cols.column * 255, cols.worstColumn);
      EXPECT_LT(rows.row, test::kSeamBound) << "row " << rows.worstRow;
      EXPECT_LT(cols.column, test::kSeamBound) << "column " << cols.worstColumn;
    }
  }
}
SAO_INSTANTIATE_APIS(ReducedResolutionApi);

}  // namespace
}  // namespace sao::exectest
