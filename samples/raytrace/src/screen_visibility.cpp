// Reference (d), converged screen-space visibility (screen_visibility.h, docs/reference.md
// "Reference (d)"). The inputs are read as reference (c) reads them (converged.cpp): csz level 0 by
// sao_z_from_depth, positions by sao_position, the normal by sao_reconstruct_normal or the supplied
// one rounded to binary16, all from effect/cpu/sao_math.h in double (-ffp-contract=off, see
// CMakeLists.txt).
//
// Why slices: every 3D direction in the plane through the eye that holds the view direction V and
// the screen direction u projects onto the screen line c + h u, so one march along that line tests
// every direction of the slice at once. In polar coordinates about V (theta from V, signed, in
// (-pi, pi]; azimuth psi in [0, pi)) the solid angle is |sin theta| dtheta dpsi and the cosine
// weight of a direction in the slice is L cos(theta - gamma) (n's projection on the slice: length
// L, angle gamma), so the cosine-weighted visibility is the psi-integral of L * (the cosine measure
// of the unblocked thetas), the inner integral exact here (the union of the blocked intervals,
// sorted) and the outer one over `slices` stratified slices, each weighted by dpsi/dphi (phi the
// screen angle) so that the slices cover the azimuth uniformly.
#include "sao/raytrace/screen_visibility.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "sampling.h"
#include "sao/constants.h"
#include "sao/cpu/parallel.h"
#include "sao_math.h"
#include "screen_inputs.h"

namespace sao::raytrace {
namespace {

using cpu::detail::Block;
using cpu::detail::Image;
using cpu::detail::Vec3;
using cpu::detail::dot;
using cpu::detail::cross;

constexpr double kPi = std::numbers::pi;

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

Status invalid(const std::string& what) {
  return Status::error(StatusCode::InvalidInput, "screenVisibility: " + what);
}

Vec3<double> scaled(Vec3<double> v, double s) { return {v.x * s, v.y * s, v.z * s}; }
Vec3<double> plus(Vec3<double> a, Vec3<double> b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3<double> normalized(Vec3<double> v) { return scaled(v, 1.0 / std::sqrt(dot(v, v))); }

using detail::linearZ;

// The cosine measure of theta in [0, x] in a slice whose projected normal is at angle gamma from
// V: the integral of cos(theta - gamma) |sin theta| (EST_SPEC "Slices"); monotone on the hemisphere.
double cosineMeasure(double x, double cosG, double sinG, double gamma) {
  const double g = (cosG - std::cos(2.0 * x - gamma) + 2.0 * x * sinG) * 0.25;
  return x >= 0 ? g : -g;
}

struct Interval {
  double lo, hi;
};

// Everything the march needs per pixel.
struct Pixel {
  int cx, cy;
  Vec3<double> C, n, V;
  double rPx;
};

// ScreenVisibilityOptions' thickness from width, in view units (scale and jump unitless).
struct WidthModel {
  bool on = false;
  double scale = 0, minT = 0, jump = 0;
};

class Marcher {
 public:
  Marcher(const Block<double>& P, const Image<double>& z0, const Image<double>* z1, double thickness, double tol,
          WidthModel width)
      : P_(P), z0_(z0), z1_(z1), T_(thickness), tol_(tol), width_(width), ortho_(P.ortho != 0) {}

  // Visibility of one pixel from `slices` slices at screen angles pi (k + xi) / slices.
  double visibility(const Pixel& px, std::uint32_t slices, double xi, bool azimuthWeight) {
    // A step of +u on the screen moves the point along w (u.x a_x, u.y a_y, 0) with w = z < 0 in
    // perspective (sao_position), 1 in ortho: D takes w's sign so that e points to the +u side.
    // The azimuth Jacobian: with f(phi) = D(phi) projected off V, f = cos f1 + sin f2, the azimuth
    // about V turns at |f1 x f2| / |f|^2 per radian of phi.
    const double ws = ortho_ ? 1.0 : -1.0;
    const Vec3<double> f1 = offV({ws * P_.proj_info.x, 0, 0}, px.V), f2 = offV({0, ws * P_.proj_info.y, 0}, px.V);
    const Vec3<double> f12 = cross(f1, f2);
    const double jacobianNumerator = std::sqrt(dot(f12, f12));
    double sumW = 0, sumWV = 0;
    for (std::uint32_t k = 0; k < slices; ++k) {
      const double phi = kPi * (k + xi) / slices;
      const double ux = std::cos(phi), uy = std::sin(phi);
      const Vec3<double> f = plus(scaled(f1, ux), scaled(f2, uy));
      const double ff = dot(f, f);
      if (!(ff > 0)) continue;
      const Vec3<double> e = scaled(f, 1.0 / std::sqrt(ff));
      const Vec3<double> a = normalized(cross(e, px.V));
      const Vec3<double> np = plus(px.n, scaled(a, -dot(px.n, a)));
      const double L = std::sqrt(dot(np, np));
      if (!(L > 0)) continue;  // n perpendicular to the slice: weight 0
      const double gamma = std::atan2(dot(np, e), dot(np, px.V));
      const double cosG = std::cos(gamma), sinG = std::sin(gamma);
      // The hemisphere's thetas; a normal facing away from the eye (|gamma| > pi/2) loses the part
      // beyond -V (theta = +-pi), which no sample can reach anyway.
      const double lo = std::max(gamma - 0.5 * kPi, -kPi), hi = std::min(gamma + 0.5 * kPi, kPi);
      const double Glo = cosineMeasure(lo, cosG, sinG, gamma), Ghi = cosineMeasure(hi, cosG, sinG, gamma);
      const double span = Ghi - Glo;
      if (!(span > 0)) continue;
      const double w = L * span * (azimuthWeight ? jacobianNumerator / ff : 1.0);
      intervals_.clear();
      march(px, ux, uy, e, +1, lo, hi);
      march(px, ux, uy, e, -1, lo, hi);
      double covered = 0;
      if (!intervals_.empty()) {
        std::sort(intervals_.begin(), intervals_.end(), [](const Interval& p, const Interval& q) { return p.lo < q.lo; });
        double a0 = intervals_[0].lo, a1 = intervals_[0].hi;
        for (std::size_t i = 1; i < intervals_.size(); ++i) {
          if (intervals_[i].lo > a1) {
            covered += cosineMeasure(a1, cosG, sinG, gamma) - cosineMeasure(a0, cosG, sinG, gamma);
            a0 = intervals_[i].lo;
          }
          a1 = std::max(a1, intervals_[i].hi);
        }
        covered += cosineMeasure(a1, cosG, sinG, gamma) - cosineMeasure(a0, cosG, sinG, gamma);
      }
      const double v = std::clamp(1.0 - covered / span, 0.0, 1.0);
      sumW += w;
      sumWV += w * v;
    }
    return sumW > 0 ? sumWV / sumW : 1.0;
  }

 private:
  static Vec3<double> offV(Vec3<double> d, Vec3<double> V) { return plus(d, scaled(V, -dot(d, V))); }

  // One side (sign +1: towards +u) of a slice: the screen line at h = 1, 2, ... <= r', each texel's
  // slab (and the second layer's) as an interval of theta, clamped to [lo, hi]. The march ends where
  // the line leaves the depth input: nothing is known beyond it (the effect's taps there read the
  // edge texel again, clamped, which says nothing about the scene), and a radius far beyond the
  // image (a scene in the wrong unit: r' up to 65536 px) would otherwise march the edge texel for
  // minutes.
  void march(const Pixel& px, double ux, double uy, Vec3<double> e, int sign, double lo, double hi) {
    if (width_.on) return marchRuns(px, ux, uy, e, sign, lo, hi);
    const int W = z0_.w, H = z0_.h;
    for (int h = 1; h <= px.rPx; ++h) {
      const int tx = px.cx + int(sign * h * ux), ty = px.cy + int(sign * h * uy);  // int() truncates, as the effect
      if (tx < 0 || ty < 0 || tx >= W || ty >= H) break;
      if (tx == px.cx && ty == px.cy) continue;  // the pixel's own texel: its slab lies behind C along V
      slab(px, tx, ty, z0_.at(tx, ty), T_, e, sign, lo, hi);
      if (z1_) slab(px, tx, ty, z1_->at(tx, ty), T_, e, sign, lo, hi);
    }
  }

  // The march with thickness from width: the line's distinct texels from C out to 2 r' (or the
  // image's edge), split into runs of continuous depth; each run's texels within r' get the run's
  // thickness.
  void marchRuns(const Pixel& px, double ux, double uy, Vec3<double> e, int sign, double lo, double hi) {
    const int W = z0_.w, H = z0_.h;
    line_.clear();
    for (int h = 0; h <= int(2.0 * px.rPx) + 1; ++h) {
      const int tx = px.cx + int(sign * h * ux), ty = px.cy + int(sign * h * uy);
      if (tx < 0 || ty < 0 || tx >= W || ty >= H) break;
      if (!line_.empty() && line_.back().x == tx && line_.back().y == ty) continue;
      line_.push_back({tx, ty, h});
    }
    auto z = [&](const LineTexel& t) { return z0_.at(t.x, t.y); };
    auto point = [&](const LineTexel& t) { return cpu::detail::position(t.x + 0.5, t.y + 0.5, z(t), P_); };
    std::size_t i = 0;
    while (i < line_.size()) {
      std::size_t j = i + 1;
      while (j < line_.size() && !cpu::detail::isSky(z(line_[j])) && !cpu::detail::isSky(z(line_[j - 1])) &&
             std::abs(z(line_[j]) - z(line_[j - 1])) <= width_.jump * std::abs(z(line_[j])))
        ++j;
      double T = T_;
      if (j < line_.size() && !cpu::detail::isSky(z(line_[i]))) {  // a run ended inside the line
        const Vec3<double> a = point(line_[i]), b = point(line_[j - 1]);
        const Vec3<double> step = cpu::detail::position(line_[i].x + 1.5, line_[i].y + 0.5, z(line_[i]), P_) - a;
        const Vec3<double> d = b - a;
        const double width = std::sqrt(dot(d, d)) + std::sqrt(dot(step, step));
        T = std::min(T_, std::max(width_.minT, width_.scale * width));  // T_ may be under minT
      }
      for (std::size_t k = i; k < j; ++k) {
        const LineTexel& t = line_[k];
        if (t.h > px.rPx) break;
        if (t.x == px.cx && t.y == px.cy) continue;  // the pixel's own texel
        slab(px, t.x, t.y, z(t), T, e, sign, lo, hi);
        if (z1_) slab(px, t.x, t.y, z1_->at(t.x, t.y), T_, e, sign, lo, hi);
      }
      i = j;
    }
  }

  void slab(const Pixel& px, int tx, int ty, double zq, double T, Vec3<double> e, int sign, double lo, double hi) {
    if (cpu::detail::isSky(zq)) return;
    const Vec3<double> S = cpu::detail::position(tx + 0.5, ty + 0.5, zq, P_);
    Vec3<double> front, back;
    if (ortho_) {
      front = {S.x, S.y, zq * (1.0 + tol_)};
      back = {S.x, S.y, zq * (1.0 + tol_) - T};
    } else {
      front = scaled(S, 1.0 + tol_);
      back = scaled(S, 1.0 + tol_ + T / -zq);  // infinite T: an infinite point, handled below
    }
    const Vec3<double> vf = front - px.C;
    if (dot(vf, vf) > P_.radius2) return;  // the radius cut
    // Angles on this side of V only (the derivation puts every sample there; the clamp keeps
    // rounding from wrapping an angle near +-pi to the other side).
    auto theta = [&](Vec3<double> v) { return sign * std::atan2(std::max(0.0, sign * dot(v, e)), dot(v, px.V)); };
    // The back end: a point, or for an infinite T the direction of the view ray behind S.
    const Vec3<double> vb = std::isfinite(T) ? back - px.C : ortho_ ? Vec3<double>{0, 0, -1} : S;
    // Both ends on or below the tangent plane (in 3D, not projected on the slice): all of the slab
    // is, so it blocks nothing (and no angles are needed: most samples on open ground). Without
    // this test a tap off the slice's line (int() truncates up to a pixel sideways) of a plane
    // through C projects onto the slice above its horizon whenever the sideways offset outweighs
    // the tolerance (grazing views), and an open plane would not be exactly 1.
    if (dot(vf, px.n) <= 0 && dot(vb, px.n) <= 0) return;
    const double tf = theta(vf), tb = theta(vb);
    const double t0 = std::max(std::min(tf, tb), lo), t1 = std::min(std::max(tf, tb), hi);
    if (t1 > t0) intervals_.push_back({t0, t1});
  }

  const Block<double>& P_;
  const Image<double>& z0_;
  const Image<double>* z1_;
  double T_, tol_;
  WidthModel width_;
  bool ortho_;
  std::vector<Interval> intervals_;
  struct LineTexel {
    int x, y, h;
  };
  std::vector<LineTexel> line_;
};

}  // namespace

Status screenVisibility(const Settings& settings, const Camera& camera, const ConvergedInputs& in,
                        const ScreenVisibilityOptions& options, FloatImage& ao) {
  ao = FloatImage{};
  if (in.depth == nullptr) return invalid("needs a depth image");  // before the options: the order of (c)'s checks
  if (options.slices == 0) return invalid("needs slices >= 1 (got 0)");
  if (options.stride == 0) return invalid("needs stride >= 1 (got 0; 1 evaluates every pixel)");
  const double thicknessMeters = options.thicknessMeters.value_or(double(settings.thickness));
  const double tolerance = options.tolerance.value_or(double(settings.depth_tolerance));
  if (!(thicknessMeters > 0))
    return invalid("the thickness must be > 0 metres or +infinity (got " + number(thicknessMeters) + ")");
  if (!(tolerance >= 0 && tolerance < 1))
    return invalid("the depth tolerance must be in [0, 1) (got " + number(tolerance) + ")");
  const bool fromWidth = options.thicknessFromWidth.value_or(settings.thickness_model == 1);
  if (fromWidth) {
    auto positive = [](double v) { return v > 0 && std::isfinite(v); };
    if (!positive(options.widthScale) || !positive(options.widthMinMeters) || !positive(options.widthJump))
      return invalid("thickness from width needs widthScale, widthMinMeters and widthJump > 0 and finite (got " +
                     number(options.widthScale) + ", " + number(options.widthMinMeters) + ", " +
                     number(options.widthJump) + ")");
  }
  gen::ParamBlock block;
  if (Status st = detail::checkScreenInputs("screenVisibility", settings, camera, in, block); !st) return st;
  const std::uint32_t g = camera.guardBand;

  const Block<double> P(block);
  const double thickness = thicknessMeters * camera.metersToViewUnits;
  const Image<double> z0 = linearZ(*in.depth, P);
  const Image<double> z1 = in.depth2 ? linearZ(*in.depth2, P) : Image<double>{};
  const std::uint32_t k = options.stride;
  ao = FloatImage(Extent{camera.width, camera.height}, 1, 1.0f);
  if (k > 1)
    for (std::uint32_t y = 0; y < camera.height; ++y)
      for (std::uint32_t x = 0; x < camera.width; ++x)
        if (x % k != 0 || y % k != 0) ao.at(x, y) = std::numeric_limits<float>::quiet_NaN();

  cpu::parallelFor(int((camera.height + k - 1) / k), options.threads, [&](int row) {
    const int py = row * int(k);
    WidthModel width;
    width.on = fromWidth;
    width.scale = options.widthScale;
    width.minT = options.widthMinMeters * camera.metersToViewUnits;
    width.jump = options.widthJump;
    Marcher marcher(P, z0, in.depth2 ? &z1 : nullptr, thickness, tolerance, width);
    for (int px = 0; px < int(camera.width); px += int(k)) {
      Pixel p;
      p.cx = px + int(g), p.cy = py + int(g);
      const double zc = z0.at(p.cx, p.cy);
      if (cpu::detail::isSky(zc)) continue;  // V = 1, as the effect writes for sky
      p.C = cpu::detail::position(p.cx + 0.5, p.cy + 0.5, zc, P);
      if (in.normals) {
        auto c = [&](std::uint32_t ch) {
          return double(quantizeHalf(in.normals->at(std::uint32_t(p.cx), std::uint32_t(p.cy), ch)));
        };
        p.n = cpu::detail::decodeNormal(Vec3<double>{c(0), c(1), c(2)});
      } else {
        p.n = cpu::detail::reconstructNormal(z0, p.cx, p.cy, p.C, P);
      }
      p.V = P.ortho != 0 ? Vec3<double>{0, 0, 1} : normalized(scaled(p.C, -1.0));
      p.rPx = cpu::detail::screenRadius(zc, P);
      std::uint64_t state = detail::pixelSeed(options.seed, std::uint32_t(px), std::uint32_t(py));
      const double xi = detail::uniform01(state);
      ao.at(std::uint32_t(px), std::uint32_t(py)) = float(marcher.visibility(p, options.slices, xi, options.azimuthWeight));
    }
  });
  return Status::success();
}

}  // namespace sao::raytrace
