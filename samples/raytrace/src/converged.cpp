// Reference (c), the converged screen-space estimator (converged.h, docs/reference.md).
//
// The formulas are the effect's own, not rewritten: effect/cpu/sao_math.h, the GLSL library as C++
// templates, instantiated here in double (sao_z_from_depth, sao_position, the normal rebuilt from
// depth, sao_tap_obscurance). That header wants -ffp-contract=off, which CMakeLists.txt sets for
// this file. What differs from the effect is only the sampling:
//
// Why stratified taps, not an integral over every texel of the disk: the disk spans r' up to
// hundreds of pixels (pi r'^2 ~ 10^5 texels per pixel at r' = 200, 10-100x the cost of 4096 taps
// at 1280x720), and the texel weights are not closed-form: the effect truncates each tap offset
// toward zero (int(h * u)), so the axis texels collect the taps of a two-texel-wide strip, and the
// density 1/(2 pi r' rho) is cut by the disk. Taps drawn from the spiral's own continuous
// distribution (uniform in radius and in angle) and truncated the same way have exactly the
// expectation of the spiral, whatever the texel grid; stratifying the radius and spreading each
// ring's taps evenly in angle (more taps on longer rings, so taps cover the disk's area about
// evenly) keeps the noise small (docs/reference.md gives its measured size).
#include "sao/raytrace/converged.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "sampling.h"
#include "screen_inputs.h"
#include "sao/constants.h"
#include "sao/cpu/parallel.h"
#include "sao_math.h"

namespace sao::raytrace {
namespace {

using cpu::detail::Block;
using cpu::detail::Image;
using cpu::detail::Vec3;

Status invalid(const std::string& what) {
  return Status::error(StatusCode::InvalidInput, "convergedEstimator: " + what);
}

using detail::linearZ;

// The unit directions of every ring, flattened: ring j holds count[j] taps at angles 2 pi k / count[j].
struct TapPattern {
  std::vector<std::uint32_t> first, count;
  std::vector<double> ux, uy;
  TapPattern(std::uint32_t rings, std::uint32_t taps) {
    const double norm = 2.0 * double(taps) / (double(rings) * rings);  // sum of (j + 0.5) is rings^2 / 2
    for (std::uint32_t j = 0; j < rings; ++j) {
      const auto n = std::max<std::uint32_t>(kMinRingTaps, std::uint32_t(std::lround(norm * (j + 0.5))));
      first.push_back(std::uint32_t(ux.size()));
      count.push_back(n);
      for (std::uint32_t k = 0; k < n; ++k) {
        const double a = 2.0 * std::numbers::pi * k / n;
        ux.push_back(std::cos(a));
        uy.push_back(std::sin(a));
      }
    }
  }
};

// sao_tap_obscurance (sao_math.h's tapObscurance) with the same operations in the same order, but
// the division skipped where the numerator max(0, v.n + z_C beta) is 0 (most taps on flat ground):
// the same value, in a loop that runs ~4096 times per pixel.
inline double term(Vec3<double> C, Vec3<double> n, double qx, double qy, double zq, const Block<double>& P) {
  if (cpu::detail::isSky(zq)) return 0.0;
  const Vec3<double> v = cpu::detail::position(qx, qy, zq, P) - C;
  const double vv = cpu::detail::dot(v, v);
  if (vv > P.radius2) return 0.0;
  const double num = cpu::detail::dot(v, n) + C.z * P.bias;
  return num > 0.0 ? num / (vv + P.epsilon) : 0.0;
}

}  // namespace

Status convergedEstimator(const Settings& settings, const Camera& camera, const ConvergedInputs& in,
                          const ConvergedOptions& options, FloatImage& ao) {
  ao = FloatImage{};
  if (options.rings == 0 || options.taps < options.rings)
    return invalid("needs rings >= 1 and taps >= rings (got " + std::to_string(options.rings) + " rings, " +
                   std::to_string(options.taps) + " taps)");
  gen::ParamBlock block;
  if (Status st = detail::checkScreenInputs("convergedEstimator", settings, camera, in, block); !st) return st;
  const std::uint32_t g = camera.guardBand;

  // The block as the effect fills it, widened to double; the sum is scaled by 2 sigma r (the
  // effect's intensity_div_s times s), since here it is a mean, not a sum of s terms.
  const Block<double> P(block);
  const double sigma2r = 2.0 * double(settings.intensity) * double(settings.radius) * camera.metersToViewUnits;
  const Image<double> z0 = linearZ(*in.depth, P);
  const Image<double> z1 = in.depth2 ? linearZ(*in.depth2, P) : Image<double>{};
  const TapPattern pattern(options.rings, options.taps);
  const int W = z0.w, H = z0.h;
  ao = FloatImage(Extent{camera.width, camera.height}, 1, 1.0f);

  cpu::parallelFor(int(camera.height), options.threads, [&](int py) {
    for (int px = 0; px < int(camera.width); ++px) {
      const int cx = px + int(g), cy = py + int(g);
      const double zc = z0.at(cx, cy);
      if (cpu::detail::isSky(zc)) continue;  // A = 1, as the effect writes for sky
      const Vec3<double> C = cpu::detail::position(cx + 0.5, cy + 0.5, zc, P);
      Vec3<double> n;
      if (in.normals) {
        auto c = [&](std::uint32_t ch) { return double(quantizeHalf(in.normals->at(std::uint32_t(cx), std::uint32_t(cy), ch))); };
        n = cpu::detail::decodeNormal(Vec3<double>{c(0), c(1), c(2)});
      } else {
        n = cpu::detail::reconstructNormal(z0, cx, cy, C, P);
      }
      const double rPx = cpu::detail::screenRadius(zc, P);
      std::uint64_t state = detail::pixelSeed(options.seed, std::uint32_t(px), std::uint32_t(py));
      double sum = 0;
      for (std::uint32_t j = 0; j < options.rings; ++j) {
        const double rho = rPx * (j + detail::uniform01(state)) / options.rings;
        const double turn = 2.0 * std::numbers::pi * detail::uniform01(state) / pattern.count[j];
        const double cr = rho * std::cos(turn), sr = rho * std::sin(turn);
        double ring = 0;
        for (std::uint32_t k = pattern.first[j], end = k + pattern.count[j]; k < end; ++k) {
          // The effect's tap: int() truncates toward zero; the texel read is clamped to level 0
          // (mipTexel at m = 0), the position is that of the unclamped pixel.
          const int tx = cx + int(cr * pattern.ux[k] - sr * pattern.uy[k]);
          const int ty = cy + int(sr * pattern.ux[k] + cr * pattern.uy[k]);
          const int mx = std::clamp(tx, 0, W - 1), my = std::clamp(ty, 0, H - 1);
          const double qx = tx + 0.5, qy = ty + 0.5;
          double o = term(C, n, qx, qy, z0.at(mx, my), P);
          if (in.depth2) o = cpu::detail::glslMax(o, term(C, n, qx, qy, z1.at(mx, my), P));
          ring += o;
        }
        sum += ring / pattern.count[j];
      }
      const double a = std::max(0.0, 1.0 - sigma2r * (sum / options.rings));
      ao.at(std::uint32_t(px), std::uint32_t(py)) = float(P.contrast == 1.0 ? a : std::pow(a, P.contrast));
    }
  });
  return Status::success();
}

}  // namespace sao::raytrace
