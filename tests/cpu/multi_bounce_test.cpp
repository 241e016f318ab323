// The multi-bounce term (setting albedo; Jimenez et al. 2016's fit f(x) = max(x, ((a x + b) x + c) x)
// applied where A is stored, sao_multi_bounce in sao_output.glsl, multiBounce in sao_math.h): the
// CPU reference's fit against the closed form, f(x) >= x and f(1) on [0, 1], albedo 0 leaving the
// fit off (and why it must be skipped rather than evaluated), and the CPU reference's output at an
// albedo being the fit of its single-bounce output, pixel for pixel, at every output pass.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "../../effect/cpu/sao_math.h"
#include "sao/constants.h"
#include "sao/presets.h"
#include "test_support.h"

namespace sao::test {
namespace {

// The fit in double with the paper's decimal constants.
double closedForm(double x, double rho) {
  const double a = 2.0404 * rho - 0.3324, b = -4.7951 * rho + 0.6417, c = 2.7552 * rho + 0.6903;
  return std::max(x, ((a * x + b) * x + c) * x);
}

ParamBlock blockFor(float albedo) {
  Settings s;
  s.albedo = albedo;
  ParamBlock p{};
  const Status st = computeConstants(s, testCamera(), DepthEncoding::Hardware, p);
  EXPECT_TRUE(st.ok()) << st.message;
  return p;
}

template <typename T>
T fit(T x, float albedo) {
  return cpu::detail::multiBounce(x, cpu::detail::Block<T>(blockFor(albedo)));
}

TEST(MultiBounce, FitMatchesTheClosedForm) {
  // By hand from the paper's constants: rho 0.5 gives a = 0.6878, b = -1.75585, c = 2.0679, and
  // f(0.5) = ((0.3439 - 1.75585) * 0.5 + 2.0679) * 0.5 = 0.6809625.
  EXPECT_NEAR(closedForm(0.5, 0.5), 0.6809625, 1e-12);
  EXPECT_NEAR(fit(0.5, 0.5f), 0.6809625, 1e-6);
  double worst = 0;
  for (float rho : {0.1f, 0.25f, 0.5f, 0.6f, 0.8f, 0.9f, 1.0f})
    for (double x : {0.0, 0.05, 0.2, 0.4, 0.5, 0.7, 0.9, 0.97, 1.0}) {
      // The block holds a, b and c as floats: |error| <= 2^-24 (|a| + |b| + |c|) < 1e-6.
      const double d = std::fabs(fit(x, rho) - closedForm(x, rho));
      EXPECT_LE(d, 1e-6) << "x " << x << ", rho " << rho;
      EXPECT_NEAR(double(fit(float(x), rho)), closedForm(x, rho), 2e-6) << "float, x " << x << ", rho " << rho;
      worst = std::max(worst, d);
    }
  std::printf("multi-bounce fit vs closed form (double): max |diff| %.3g\n", worst);
  // It brightens: at x = 0.5, rho 0.8 gives 0.811125 (rho 0.5: 0.681).
  EXPECT_NEAR(fit(0.5, 0.8f), closedForm(0.5, 0.8), 1e-6);
  EXPECT_GT(fit(0.5, 0.8f), 0.8);
}

// f(x) >= x on [0, 1] for every albedo (the max), and f(1) = max(1, a + b + c) with
// a + b + c = 0.9996 + 0.0005 rho: exactly 1 up to rho = 0.8, at most 1.0001 (rho = 1) beyond,
// which the store's clamp to [0, 1] takes back to 1.
TEST(MultiBounce, NeverDarkensAndKeepsOneWithinTheFitsRounding) {
  double highest = 0;
  for (int k = 1; k <= 64; ++k) {
    const float rho = float(k) / 64.0f;
    const cpu::detail::Block<double> d(blockFor(rho));
    const cpu::detail::Block<float> f(blockFor(rho));
    for (int i = 0; i <= 1024; ++i) {
      const double x = double(i) / 1024.0;
      ASSERT_GE(cpu::detail::multiBounce(x, d), x) << "rho " << rho;
      ASSERT_GE(cpu::detail::multiBounce(float(x), f), float(x)) << "rho " << rho;
    }
    const double one = cpu::detail::multiBounce(1.0, d);
    EXPECT_GE(one, 1.0);
    EXPECT_LE(one, 1.0001 + 1e-6) << "rho " << rho;
    if (rho <= 0.75f) { EXPECT_EQ(one, 1.0) << "rho " << rho; }
    EXPECT_NEAR(one, std::max(1.0, 0.9996 + 0.0005 * double(rho)), 1e-6) << "rho " << rho;
    highest = std::max(highest, one);
  }
  std::printf("multi-bounce f(1): at most %.7f (rho 1)\n", highest);
}

// Albedo 0: the block's multi_bounce is 0 and a, b, c are 0, so the store keeps A itself; the block
// differs from an albedo's only in those four members. Evaluated, the fit at rho 0 would not be
// the identity: ((-0.3324 x + 0.6417) x + 0.6903) x exceeds x for x in about (0.963, 0.967).
TEST(MultiBounce, AlbedoZeroSkipsTheFit) {
  const ParamBlock off = blockFor(0.0f);
  EXPECT_EQ(off.multi_bounce, 0);
  EXPECT_EQ(off.bounce_a, 0.0f);
  EXPECT_EQ(off.bounce_b, 0.0f);
  EXPECT_EQ(off.bounce_c, 0.0f);
  ParamBlock on = blockFor(0.5f);
  EXPECT_EQ(on.multi_bounce, 1);
  EXPECT_EQ(on.bounce_a, float(2.0404 * 0.5 - 0.3324));
  EXPECT_EQ(on.bounce_b, float(-4.7951 * 0.5 + 0.6417));
  EXPECT_EQ(on.bounce_c, float(2.7552 * 0.5 + 0.6903));
  on.multi_bounce = off.multi_bounce;
  on.bounce_a = off.bounce_a;
  on.bounce_b = off.bounce_b;
  on.bounce_c = off.bounce_c;
  EXPECT_EQ(std::memcmp(&on, &off, sizeof on), 0) << "the albedo reaches no other member of the block";
  for (double x : {0.0, 0.3, 0.965, 1.0}) EXPECT_EQ(fit(x, 0.0f), x);
  EXPECT_GT(closedForm(0.965, 0.0), 0.965) << "the fit at rho 0 is not the identity: it must be skipped";
}

// The output at an albedo is the fit of the single-bounce output (Double: unrounded), clamped to
// [0, 1], at every pass that stores the output: upsample (medium, half resolution), output (reference,
// full resolution after the blur) and ao_sample_output (no blur, full resolution); with the
// multiply blend, the caller's texel times that.
TEST(MultiBounce, OutputIsTheFitOfTheSingleBounceOutput) {
  const Camera cam = testCamera();
  Settings direct = presetSettings(Preset::Reference);
  direct.blur_radius = 0;
  const std::pair<const char*, Settings> configs[] = {
      {"medium", presetSettings(Preset::Medium)}, {"reference", presetSettings(Preset::Reference)}, {"direct", direct}};
  for (const Scene& scene : {sphereOnPlaneScene(), stairsScene(), creaseScene(2.0)}) {
    const DepthImage depth = renderDepth(scene, cam, DepthFormat::D32F);
    for (const auto& [name, base] : configs) {
      for (bool multiply : {false, true}) {
        SCOPED_TRACE(scene.name + " " + name + (multiply ? " multiply" : ""));
        FloatImage target({cam.width, cam.height}, 1);
        for (std::size_t i = 0; i < target.data.size(); ++i) target.data[i] = float(i % 7 + 1) / 8.0f;
        cpu::Inputs in;
        in.depth = &depth;
        if (multiply) {
          in.output = &target;
          in.outputBlend = OutputBlend::Multiply;
        }
        const cpu::Result single = runOrFail(base, cam, in, cpu::Precision::Double);
        for (float rho : {0.3f, 0.6f, 1.0f}) {
          Settings s = base;
          s.albedo = rho;
          const cpu::Result bounced = runOrFail(s, cam, in, cpu::Precision::Double);
          ASSERT_EQ(bounced.ao.data.size(), single.ao.data.size());
          double worst = 0, brightest = 0;
          for (std::size_t i = 0; i < single.ao.data.size(); ++i) {
            const double c = multiply ? double(target.data[i]) : 1.0;
            const double x = double(single.ao.data[i]) / c;  // A, the value the store took
            const double want = c * std::clamp(closedForm(x, rho), 0.0, 1.0);
            worst = std::max(worst, std::fabs(double(bounced.ao.data[i]) - want));
            brightest = std::max(brightest, double(bounced.ao.data[i]) - double(single.ao.data[i]));
            ASSERT_LE(bounced.ao.data[i], float(c)) << "pixel " << i << ": above 1 (times the texel)";
          }
          EXPECT_LE(worst, 2e-6) << "rho " << rho;
          EXPECT_GT(brightest, 0.02) << "rho " << rho << ": the fit changed nothing";
        }
      }
    }
  }
}

}  // namespace
}  // namespace sao::test
