// resolution_divisor 2 and 4 on OpenGL against the CPU reference (float): the final AO, the
// reduced raw AO and the reduced (A, key) image the upsample reads, at the reference tests'
// bounds (at least 99.9% of the pixels within 2/255, none beyond 4/255), at 160x90 with a guard
// band and at the odd sizes 641x359 and 97x61; and no seam at the odd sizes (seam_metric.h).
#include <epoxy/gl.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "gl_support.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "seam_metric.h"

namespace sao::gltest {
namespace {

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

Settings reduced(int divisor) {
  Settings s = presetSettings(Preset::Medium);
  s.resolution_divisor = divisor;
  return s;
}

// One GL render of `depth`; the final AO and, when `ref` is given, the comparisons with it.
FloatImage render(gl::Effect& effect, const Camera& cam, const Settings& settings, const DepthImage& depth,
                  GlDepth format, const cpu::Result* ref, const std::string& name) {
  const GLuint depthTex = uploadDepth(depth, format);
  gl::Inputs gi;
  gi.depth = {depthTex, internalFormat(format)};
  const Status st = effect.render(cam, settings, gi);
  EXPECT_TRUE(st.ok()) << st.message;
  FloatImage ao = readTexture(effect.aoTexture(), 1);
  if (ref != nullptr && st.ok()) {
    EXPECT_EQ(effect.plan().describe(), ref->plan.describe()) << name;
    EXPECT_EQ(std::memcmp(&effect.params(), &ref->params, sizeof ref->params), 0) << name << ": parameter blocks differ";
    const FloatImage raw = readTexture(effect.texture(gen::ResourceId::ao_raw), 2);
    const FloatImage low = readTexture(effect.texture(gen::ResourceId::ao_low), 2);
    const FloatImage& refLow = ref->images[static_cast<std::size_t>(gen::ResourceId::ao_low)].at(0);
    const Agreement f = compare(ao, ref->ao, 0, kWithin, kNever, name + "_final");
    const Agreement r = compare(raw, ref->aoRaw, 0, kWithin, kNever, name + "_raw");
    const Agreement l = compare(low, refLow, 0, kWithin, kNever, name + "_low");
    const Agreement k = compare(low, refLow, 1, 0.0, 0.0, name + "_low_key");
    std::printf("AGREEMENT %-26s final max %.3f/255 p99.9 %.3f/255 | raw max %.3f/255 | low max %.3f/255\n",
                name.c_str(), f.maxAbs * 255, f.p999 * 255, r.maxAbs * 255, l.maxAbs * 255);
    EXPECT_TRUE(acceptable(f)) << name << " final: max " << f.maxAbs * 255 << "/255, " << f.beyond << " beyond 4/255";
    EXPECT_TRUE(acceptable(r)) << name << " raw: max " << r.maxAbs * 255 << "/255, " << r.beyond << " beyond 4/255";
    EXPECT_TRUE(acceptable(l)) << name << " low: max " << l.maxAbs * 255 << "/255, " << l.beyond << " beyond 4/255";
    EXPECT_EQ(k.maxAbs, 0.0) << name << ": the low keys are csz texels, copied";
  }
  deleteTexture(depthTex);
  return ao;
}

struct SizeCase {
  std::uint32_t width, height, guard;
};

class ReducedResolution : public GlTest {};

TEST_F(ReducedResolution, MatchesTheCpuReference) {
  auto effect = makeEffect();
  for (const SizeCase sc : {SizeCase{160, 90, 8}, SizeCase{641, 359, 0}, SizeCase{97, 61, 3}}) {
    const Camera cam = camera(sc.width, sc.height, sc.guard);
    for (const char* scene : {"plane", "crease", "sphere", "stairs", "rods"}) {
      const bool big = sc.width > 200;
      if (big && std::string(scene) == "plane") continue;  // the seam test runs it
      const GlDepth format = std::string(scene) == "stairs" ? GlDepth::D24 : GlDepth::D32F;
      const DepthImage depth = test::renderDepth(sceneByName(scene), cam, cpuFormat(format));
      for (int d : {2, 4}) {
        const std::string name = std::string(scene) + "_" + std::to_string(sc.width) + "x" +
                                 std::to_string(sc.height) + "_d" + std::to_string(d);
        SCOPED_TRACE(name);
        cpu::Result ref;
        const Status cst = cpu::run(reduced(d), cam, {&depth}, cpu::Options{cpu::Precision::Float, 2}, ref);
        ASSERT_TRUE(cst.ok()) << cst.message;
        render(*effect, cam, reduced(d), depth, format, &ref, name);
      }
    }
  }
}

// Divisor 1 after a reduced frame: the effect goes back to the full-resolution plan and output.
TEST_F(ReducedResolution, BackToFullResolution) {
  const Camera cam = camera(160, 90, 8);
  const DepthImage depth = test::renderDepth(sceneByName("sphere"), cam, DepthFormat::D32F);
  auto effect = makeEffect();
  render(*effect, cam, reduced(4), depth, GlDepth::D32F, nullptr, "");
  cpu::Result ref;
  ASSERT_TRUE(cpu::run(reduced(1), cam, {&depth}, cpu::Options{cpu::Precision::Float, 2}, ref).ok());
  const FloatImage ao = render(*effect, cam, reduced(1), depth, GlDepth::D32F, nullptr, "");
  const PlannedImage* low = effect->plan().image(gen::ResourceId::ao_low);
  ASSERT_NE(low, nullptr) << "the blur's image";
  EXPECT_EQ(low->extent, (Extent{160, 90})) << "full resolution: ao_low is the viewport's size";
  const Agreement f = compare(ao, ref.ao, 0, kWithin, kNever, "back_to_full");
  EXPECT_TRUE(acceptable(f)) << "max " << f.maxAbs * 255 << "/255";
}

// No row or column of the output stands out at odd sizes: an open plane is 1 everywhere, the
// creases' row (vertical crease) and column (horizontal crease) means are flat (seam_metric.h).
TEST_F(ReducedResolution, NoSeamAtOddSizes) {
  auto effect = makeEffect();
  for (const SizeCase sc : {SizeCase{641, 359, 0}, SizeCase{97, 61, 0}}) {
    const Camera cam = camera(sc.width, sc.height, sc.guard);
    const DepthImage plane = test::renderDepth(test::planeScene(3.0), cam, DepthFormat::D32F);
    const DepthImage vertical = test::renderDepth(test::creaseScene(2.0), cam, DepthFormat::D32F);
    const DepthImage horizontal = test::renderDepth(test::horizontalCreaseScene(2.0), cam, DepthFormat::D32F);
    for (int d : {2, 4}) {
      const FloatImage p = render(*effect, cam, reduced(d), plane, GlDepth::D32F, nullptr, "");
      EXPECT_EQ(*std::min_element(p.data.begin(), p.data.end()), 1.0f) << sc.width << " d=" << d;
      const std::uint32_t margin = 2 * d;
      const test::SeamScore rows = test::seamScore(render(*effect, cam, reduced(d), vertical, GlDepth::D32F, nullptr, ""), margin);
      const test::SeamScore cols = test::seamScore(render(*effect, cam, reduced(d), horizontal, GlDepth::D32F, nullptr, ""), margin);
      std::printf("GL seam %ux%u d=%d: rows %.4f/255 (row %u), columns %.4f/255 (column %u)\n", sc.width, sc.height, d,
                  rows.row * 255, rows.worstRow, cols.column * 255, cols.worstColumn);
      EXPECT_LT(rows.row, test::kSeamBound) << sc.width << " d=" << d << " row " << rows.worstRow;
      EXPECT_LT(cols.column, test::kSeamBound) << sc.width << " d=" << d << " column " << cols.worstColumn;
    }
  }
}

}  // namespace
}  // namespace sao::gltest
