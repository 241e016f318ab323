// depthConventionWarnings: what a depth buffer's values say about the convention it is read with.
// The math (docs/effect-math.md, section 2.1): perspective window depth d is affine in 1/z, so with
// an infinite far plane standard depth is d = 1 - n/D and reversed-Z d = n/D at distance D from the
// camera (n the near distance; a finite far plane changes this little). Reading one as the other
// maps d to 1 - d: the distance becomes nD/(D - n), which puts everything beyond 2n within 2n, and
// most of a scene within a hair of the near plane. Window depth is also affine in screen position
// on a flat surface (1/z is), while a distance is not (its reciprocal is): that tells linear depth
// normalised to [0, 1] from window depth. Orthographic window depth is affine in the distance
// itself, so only its sky (the clear value: 1 standard, 0 reversed-Z) tells the conventions apart.
#include "sao/samples/depth_convention.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

#include "sao/constants.h"

namespace sao::samples {

namespace {

std::string format(const char* pattern, ...) {
  char text[512];
  va_list args;
  va_start(args, pattern);
  std::vsnprintf(text, sizeof text, pattern, args);
  va_end(args);
  return text;
}

// The median of t = n/D (1 - d standard, d reversed-Z) above which most of a perspective buffer's
// geometry lies within twice the near distance under the declared reading: the other one's mark.
constexpr double kFlippedMedian = 0.5;
// Flat-surface votes for linear depth: at least this many, one per kLinearVoteShare interior texels
// (a linear buffer gets about one per texel, window depth of the built-in scenes below one per 170,
// from curved surfaces and silhouettes), and kVoteMajority times those for window depth.
constexpr std::size_t kMinLinearVotes = 32;
constexpr std::size_t kLinearVoteShare = 10;
constexpr std::size_t kVoteMajority = 4;
// Orthographic: the other convention's clear value on at least 1/kOrthoSkyShare of the texels.
constexpr std::size_t kOrthoSkyShare = 200;

struct Region {
  std::uint32_t x0 = 0, y0 = 0, width = 0, height = 0;
};

// The camera's viewport inside the depth image, or the whole image when the extents disagree.
Region viewport(const DepthImage& depth, const Camera& camera) {
  const std::uint32_t g = camera.guardBand;
  if (std::uint64_t(camera.width) + 2ull * g == depth.extent.width &&
      std::uint64_t(camera.height) + 2ull * g == depth.extent.height && camera.width > 0 && camera.height > 0)
    return {g, g, camera.width, camera.height};
  return {0, 0, depth.extent.width, depth.extent.height};
}

// A near or far distance for the messages ("inf" for an infinite far plane).
std::string distance(double d) { return std::isfinite(d) ? format("%g", d) : std::string("inf"); }

// ---- LinearZ: geometry is finite and negative; positive, zero and non-finite values are sky.

std::vector<std::string> linearZWarnings(const std::vector<double>& v) {
  std::size_t geometry = 0, positive = 0, zero = 0, nonFinite = 0;
  double lo = INFINITY, hi = -INFINITY;
  for (double z : v) {
    if (!std::isfinite(z)) {
      ++nonFinite;
    } else if (z < 0) {
      ++geometry;
    } else if (z > 0) {
      ++positive;
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    } else {
      ++zero;
    }
  }
  const std::string why =
      "LinearZ holds camera-space z, negative in front of the camera; positive distances along the view axis "
      "(e.g. a Blender Z pass) are read with --depth-distances";
  if (positive > geometry) {
    const std::string values = format("%g to %g", lo, hi);
    if (geometry == 0)
      return {format("no geometry: every one of the %zu depth texels is sky, so the AO is 1 everywhere: %s of them "
                     "are positive (%s), which LinearZ reads as sky: ",
                     v.size(), positive == v.size() ? "all" : format("%zu", positive).c_str(), values.c_str()) +
              why};
    return {format("%zu of the %zu depth texels are positive (%s), which LinearZ reads as sky (AO 1): ", positive,
                   v.size(), values.c_str()) +
            why};
  }
  if (geometry == 0) {
    std::string values;
    auto add = [&values](std::size_t n, const char* what) {
      if (n) values += (values.empty() ? "" : ", ") + format("%zu %s", n, what);
    };
    add(zero, "0");
    add(nonFinite, "NaN or infinite");
    return {format("no geometry: every one of the %zu depth texels is sky (%s; LinearZ geometry is finite and "
                   "negative), so the AO is 1 everywhere",
                   v.size(), values.c_str())};
  }
  return {};
}

// ---- Hardware depth (D16, D24, D32F): window depth in [0, 1].

// The rounding step of the stored values: what two equal depths may differ by. A D32F buffer may
// hold integer depth converted to float (a camera-less file of D16 depth), whose steps are coarser
// than a float's: D16's when every value lies on its grid, else at least D24's.
double storageStep(DepthFormat storage, const std::vector<double>& interior) {
  if (storage == DepthFormat::D16) return 1.0 / 65535.0;
  if (storage == DepthFormat::D24 || interior.empty()) return 1.0 / 16777215.0;
  for (double v : interior)
    if (std::abs(v * 65535.0 - std::round(v * 65535.0)) > 0.01) return 1.0 / 16777215.0;
  return 1.0 / 65535.0;
}

// Votes of three neighbouring texels a, b, c (all strictly inside (0, 1)) on whether the buffer is
// window depth (d affine on a flat surface: a - 2b + c = 0) or a distance (1/d affine). A stencil
// votes only when one reading is flat and the other measurably curved (beyond the rounding); one
// that fits neither (a silhouette) does not vote.
struct Votes {
  std::size_t window = 0, linear = 0;
  void add(double step, double a, double b, double c) {
    const double s1 = std::abs(c - a), e1 = std::abs(a - 2 * b + c);
    const double s2 = std::abs(1 / c - 1 / a), e2 = std::abs(1 / a - 2 / b + 1 / c);
    if (!(s1 > 0 && s2 > 0)) return;
    const float top = float(std::max({a, b, c}));
    const double q = std::max(step, double(std::nextafter(top, 2.0f)) - double(top));
    const double low = std::min({a, b, c});
    const double noise1 = 2 * q, noise2 = 2 * q / (low * low);
    const double r1 = e1 / s1, r2 = e2 / s2;
    if (std::min(r1, r2) > 0.25) return;
    if (e1 > 8 * noise1 && r1 > double(kVoteMajority) * r2) ++linear;
    else if (e2 > 8 * noise2 && r2 > double(kVoteMajority) * r1) ++window;
  }
};

struct HardwareTally {
  std::size_t geometry = 0;      // geometry under the declared convention
  std::size_t declaredSky = 0;   // at or beyond the declared clear value (or not a depth at all)
  std::size_t otherSky = 0;      // exactly the other convention's clear value
  double lo = INFINITY, hi = -INFINITY;
  std::vector<double> interior;  // the values strictly inside (0, 1): geometry under either convention
  Votes votes;                   // perspective only
};

HardwareTally tallyHardware(const std::vector<double>& v, const Region& r, const Camera& camera,
                            const DepthModel& model, DepthFormat storage) {
  HardwareTally t;
  const double otherClear = camera.reversedZ ? 1.0 : 0.0;
  for (double d : v) {
    if (std::isfinite(d)) {
      t.lo = std::min(t.lo, d);
      t.hi = std::max(t.hi, d);
    }
    const bool sky = !(d >= 0 && d <= 1) || (camera.reversedZ ? d <= 0 : d >= 1);
    t.declaredSky += sky;
    t.otherSky += d == otherClear;
    if (!sky) {
      const double z = linearZ(model, camera.kind, d);
      t.geometry += std::isfinite(z) && z < 0;
    }
    if (d > 0 && d < 1) t.interior.push_back(d);
  }
  if (camera.kind != ProjectionKind::Perspective) return t;
  const double step = storageStep(storage, t.interior);
  auto inside = [](double d) { return d > 0 && d < 1; };
  auto at = [&](std::uint32_t x, std::uint32_t y) { return v[std::size_t(y) * r.width + x]; };
  // Neighbours k texels apart, about 1/64 of the smaller side: the curvature a wrong reading shows
  // over k texels grows with k squared, the rounding does not, so a large image tells as well.
  const std::uint32_t k = std::max(1u, std::uint32_t(std::lround(std::min(r.width, r.height) / 64.0)));
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x) {
      const double b = at(x, y);
      if (!inside(b)) continue;
      if (x >= k && x + k < r.width && inside(at(x - k, y)) && inside(at(x + k, y)))
        t.votes.add(step, at(x - k, y), b, at(x + k, y));
      if (y >= k && y + k < r.height && inside(at(x, y - k)) && inside(at(x, y + k)))
        t.votes.add(step, at(x, y - k), b, at(x, y + k));
    }
  return t;
}

const char* conventionName(bool reversedZ) { return reversedZ ? "reversed-Z" : "standard"; }

// The advice for a buffer that looks like the other convention than the declared one.
std::string flagAdvice(bool declaredReversed) {
  return declaredReversed ? "leave out --reversed-z (a depth file with its own camera: set its sao.reversedZ to 0)"
                          : "give --reversed-z (a depth file with its own camera: set its sao.reversedZ to 1)";
}

std::vector<std::string> hardwareWarnings(const std::vector<double>& v, const Region& r, const Camera& camera,
                                          const DepthModel& model, const ParamBlock& block, DepthFormat storage) {
  HardwareTally t = tallyHardware(v, r, camera, model, storage);
  const bool rev = camera.reversedZ;
  const double clear = rev ? 0.0 : 1.0, otherClear = rev ? 1.0 : 0.0;

  if (t.geometry == 0) {
    const std::string values =
        t.lo > t.hi    ? std::string("all NaN or infinite")
        : t.lo == t.hi ? format("all %g, the %s clear value", t.lo, conventionName(rev))
                       : format("values %g to %g: the clear value %g or outside [0, 1]", t.lo, t.hi, clear);
    return {format("no geometry: every one of the %zu depth texels is sky (%s), so the AO is 1 everywhere: nothing "
                   "in view lies between the near plane (%s view units) and the far plane (%s): is the near plane "
                   "(--near) beyond the scene, the camera looking away from it, or the depth buffer empty?",
                   v.size(), values.c_str(), distance(model.nearDistance).c_str(),
                   distance(model.farDistance).c_str())};
  }

  // The sky says which convention the buffer has when exactly one clear value occurs.
  const bool skyIsOther = t.otherSky > 0 && t.declaredSky == 0;
  const bool skyAgrees = t.declaredSky > 0 && t.otherSky == 0;
  const std::string skyClause =
      skyIsOther ? format("%s%zu texels are %g, %s depth's clear value (sky), and none is %g; ",
                          t.otherSky == v.size() ? "all " : "", t.otherSky, otherClear, conventionName(!rev), clear)
                 : std::string();
  const std::string looks = format("the depth looks %s but is read as %s depth: ", conventionName(!rev),
                                   conventionName(rev));

  if (camera.kind == ProjectionKind::Orthographic) {
    if (skyIsOther && t.otherSky * kOrthoSkyShare >= v.size())
      return {looks + skyClause + flagAdvice(rev)};
    return {};
  }

  if (t.interior.empty())  // only 0 and 1: the other convention's empty buffer reads as the near plane
    return skyIsOther ? std::vector<std::string>{looks + skyClause + "read as " + conventionName(rev) +
                                                 " depth they are the near plane: " + flagAdvice(rev)}
                      : std::vector<std::string>{};

  // t = n/D under the declared reading (infinite far): its median says where most geometry lies.
  std::vector<double> nearness(t.interior.size());
  std::transform(t.interior.begin(), t.interior.end(), nearness.begin(),
                 [rev](double d) { return rev ? d : 1 - d; });
  const auto mid = nearness.begin() + nearness.size() / 2;
  std::nth_element(nearness.begin(), mid, nearness.end());
  const double dMedian = rev ? *mid : 1 - *mid;
  const double asRead = -linearZ(model, camera.kind, dMedian), asOther = -linearZ(model, camera.kind, 1 - dMedian);
  const double n = model.nearDistance;
  auto radiusPx = [&block](double dist) { return double(block.radius) * block.proj_scale / dist; };

  const bool linear = t.votes.linear >= kMinLinearVotes && t.votes.linear * kLinearVoteShare >= t.interior.size() &&
                      t.votes.linear >= kVoteMajority * t.votes.window;
  if (linear)
    return {format("the depth looks linear in distance (normalised to [0, 1]?), not %s window depth: on flat "
                   "surfaces its reciprocal changes evenly across the image where window depth itself would (%zu "
                   "neighbourhoods against %zu); read as window depth the median geometry lies %.3g x the near "
                   "distance away (the radius spans %.3g px there): scale it back to view units and give it with "
                   "--depth-distances, or store camera-space z as LinearZ",
                   conventionName(rev), t.votes.linear, t.votes.window, asRead / n, radiusPx(asRead))};

  if (*mid > kFlippedMedian && !skyAgrees)
    return {looks + skyClause +
            format("read as %s, the median geometry lies %.3g x the near distance away (%.3g view units; the radius "
                   "spans %.3g px there), read as %s %.3g x (%.3g px): ",
                   conventionName(rev), asRead / n, asRead, radiusPx(asRead), conventionName(!rev), asOther / n,
                   radiusPx(asOther)) +
            flagAdvice(rev)};
  return {};
}

}  // namespace

std::vector<std::string> depthConventionWarnings(const DepthImage& depth, const Camera& camera,
                                                 const Settings& settings) {
  const Region r = viewport(depth, camera);
  if (r.width == 0 || r.height == 0 || depth.samples == 0 ||
      depth.texels.size() != std::size_t(depth.extent.width) * depth.extent.height * depth.samples)
    return {};
  DepthModel model;
  ParamBlock block;
  const DepthEncoding encoding =
      depth.format == DepthFormat::LinearZ ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  if (!analyze(camera, model) || !computeConstants(settings, camera, encoding, block)) return {};
  std::vector<double> v;  // sample 0 of each viewport texel, row by row
  v.reserve(std::size_t(r.width) * r.height);
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x) v.push_back(depth.value(r.x0 + x, r.y0 + y));
  if (depth.format == DepthFormat::LinearZ) return linearZWarnings(v);
  return hardwareWarnings(v, r, camera, model, block, depth.format);
}

}  // namespace sao::samples
