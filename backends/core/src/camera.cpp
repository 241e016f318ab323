#include "sao/camera.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "sao/plan.h"  // kMaxImageSide

namespace sao {
namespace {

double at(const Camera& c, int row, int col) { return c.projection[col * 4 + row]; }

Status bad(const std::string& m) { return Status::error(StatusCode::InvalidCamera, m); }

constexpr double kPoleTolerance = 1e-12;

// Stored depth d = scale * ndc.z + offset.
void depthMapping(ClipDepth clip, double& scale, double& offset) {
  scale = clip == ClipDepth::ZeroToOne ? 1.0 : 0.5;
  offset = clip == ClipDepth::ZeroToOne ? 0.0 : 0.5;
}

}  // namespace

// Declared near/far planes that the matrix, read with the declared clip range, does not reproduce.
// 1e-3 relative: a matrix built in float still passes, a [-1,1] / [0,1] mix-up (about 2x) does not.
static Status checkExpected(const Camera& cam, const char* what, const char* plane, double expected, double actual) {
  if (expected == 0) return Status::success();
  if (std::isnan(expected) || expected < 0)
    return bad(std::string("expected") + what + " must be >= 0 (0: not checked)");
  // An infinite plane matches only an infinite one (|finite - inf| <= 1e-3 * inf would pass).
  if (expected == actual || (std::isfinite(expected) && std::fabs(actual - expected) <= 1e-3 * expected))
    return Status::success();
  char text[200];
  std::snprintf(text, sizeof text, "the projection read with clipDepth = %s has its %s plane at %g, not at expected%s = %g",
                cam.clipDepth == ClipDepth::ZeroToOne ? "[0,1]" : "[-1,1]", plane, actual, what, expected);
  return bad(std::string(text) + ": check clipDepth");
}

static Status analyzeMatrix(const Camera& cam, DepthModel& m);

// The declared clip range as the messages name it: a far plane that comes out wrong is most often
// a matrix built for the other range.
static std::string clipText(const Camera& cam) { return cam.clipDepth == ClipDepth::ZeroToOne ? "[0,1]" : "[-1,1]"; }

// A standard matrix built with near and far swapped is exactly a reversed-Z matrix with them in
// order (and the other way round): the matrix cannot tell the two mistakes apart, so name both.
static Status reversedMismatch(const Camera& cam) {
  return bad(std::string("declared ") + (cam.reversedZ ? "reversed-Z" : "standard depth") +
             ", but the projection maps the near plane to depth " + (cam.reversedZ ? "0" : "1") +
             ": set reversedZ = " + (cam.reversedZ ? "false" : "true") +
             ", or, if the matrix was built with the near and far distances swapped, swap them");
}

Status analyze(const Camera& cam, DepthModel& m) {
  if (Status st = analyzeMatrix(cam, m); !st.ok()) return st;
  if (Status st = checkExpected(cam, "Near", "near", cam.expectedNear, m.nearDistance); !st.ok()) return st;
  return checkExpected(cam, "Far", "far", cam.expectedFar, m.farDistance);
}

static Status analyzeMatrix(const Camera& cam, DepthModel& m) {
  for (int i = 0; i < 16; ++i)
    if (!std::isfinite(cam.projection[i])) {
      // Element (row i % 4, column i / 4). An infinite P22 or P23 comes from near == far.
      char text[160];
      std::snprintf(text, sizeof text, "projection matrix has a non-finite element P%d%d (row %d, column %d) = %g",
                    i % 4, i / 4, i % 4, i / 4, cam.projection[i]);
      return bad(std::string(text) + (i == 10 || i == 14 ? ": were the near and far planes equal when it was built?" : ""));
    }
  if (cam.width == 0 || cam.height == 0) return bad("viewport size is " + std::to_string(cam.width) + "x" +
                                                    std::to_string(cam.height) + "; both must be > 0");
  // Outside this range float view-space positions lose the precision the effect needs (normals
  // reconstructed from pixel spans underflow below ~1e-10): docs/STABILITY.md.
  if (!std::isfinite(cam.metersToViewUnits) || cam.metersToViewUnits < 1e-6 || cam.metersToViewUnits > 1e6)
  {
    char value[32];
    std::snprintf(value, sizeof value, "%g", cam.metersToViewUnits);
    return bad(std::string("metersToViewUnits = ") + value + " is outside the supported range [1e-6, 1e6]");
  }
  if (at(cam, 0, 0) == 0 || at(cam, 1, 1) == 0) return bad("projection has a zero x or y scale (P00 or P11)");

  double s = 0, o = 0;
  depthMapping(cam.clipDepth, s, o);
  const double C = at(cam, 2, 2), D = at(cam, 2, 3);
  m.depthAtNear = cam.reversedZ ? 1.0 : 0.0;
  m.depthAtFar = cam.reversedZ ? 0.0 : 1.0;

  if (cam.kind == ProjectionKind::Perspective) {
    if (at(cam, 3, 2) != -1.0 || at(cam, 3, 3) != 0.0 || at(cam, 3, 0) != 0.0 || at(cam, 3, 1) != 0.0)
      return bad("declared perspective, but the bottom row of the projection is not (0, 0, -1, 0)");
    if (at(cam, 2, 0) != 0.0 || at(cam, 2, 1) != 0.0) return bad("projection's depth row mixes in x or y");
    // ndc.z = -C - D / z, so d = (o - s*C) - s*D / z  =>  z = -s*D / (d + s*C - o).
    m.c0 = -s * D;
    m.c1 = 1.0;
    m.c2 = s * C - o;
    if (m.c0 == 0) return bad("projection's depth row has no 1/z term (P23 == 0)");
    const double zNear = m.c0 / (m.depthAtNear * m.c1 + m.c2);
    const double farDen = m.depthAtFar * m.c1 + m.c2;
    // The declared near end must be the end closer to the eye; otherwise reversedZ is wrong.
    const double nearDen = m.depthAtNear * m.c1 + m.c2;
    const bool poleAtNear = std::fabs(nearDen) <= kPoleTolerance * std::fmax(1.0, std::fabs(m.c2));
    const double zAtFar = m.c0 / farDen;
    if (poleAtNear || (zNear < 0 && zAtFar < 0 && std::isfinite(zAtFar) && -zAtFar < -zNear))
      return reversedMismatch(cam);
    // An infinite far plane puts the clear depth exactly at the pole (C = -1 or 0 as the paper's
    // c = [zn, -1, +1]). The tolerance is relative rounding of a double computation; a finite far
    // plane even 1e10 times the near distance is still finite.
    const bool atPole = std::fabs(farDen) <= kPoleTolerance * std::fmax(1.0, std::fabs(m.c2));
    if (!(zNear < 0) || !std::isfinite(zNear)) {
      const double zOther = m.c0 / (m.depthAtFar * m.c1 + m.c2);
      if (zOther < 0 && std::isfinite(zOther) && !atPole) return reversedMismatch(cam);
      return bad("projection puts the near plane at or behind the eye (near <= 0)");
    }
    m.nearDistance = -zNear;
    if (cam.infiniteFar) {
      if (!atPole)
        return bad("declared an infinite far plane, but the projection read with clipDepth = " + clipText(cam) +
                   " has a far plane at " + std::to_string(-m.c0 / farDen) +
                   " view units: check clipDepth, or set infiniteFar = false");
      m.farDistance = std::numeric_limits<double>::infinity();
    } else {
      if (atPole)
        return bad("the projection read with clipDepth = " + clipText(cam) +
                   " has an infinite far plane: set infiniteFar = true, or check clipDepth");
      const double zFar = m.c0 / farDen;
      if (!(zFar < 0) || -zFar <= m.nearDistance)
        return bad("the projection read with clipDepth = " + clipText(cam) +
                   " has its far plane not beyond its near plane: check clipDepth and reversedZ");
      m.farDistance = -zFar;
    }
    return Status::success();
  }

  if (at(cam, 3, 2) != 0.0 || at(cam, 3, 3) != 1.0 || at(cam, 3, 0) != 0.0 || at(cam, 3, 1) != 0.0)
    return bad("declared orthographic, but the bottom row of the projection is not (0, 0, 0, 1)");
  if (cam.infiniteFar) return bad("an orthographic projection cannot have an infinite far plane");
  if (C == 0) return bad("orthographic projection has no depth scale (P22 == 0)");
  // ndc.z = C*z + D, d = s*ndc.z + o  =>  z = d / (s*C) - (o + s*D) / (s*C).
  m.c0 = 0;
  m.c1 = 1.0 / (s * C);
  m.c2 = -(o + s * D) / (s * C);
  const double zNear = m.depthAtNear * m.c1 + m.c2, zFar = m.depthAtFar * m.c1 + m.c2;
  if (!(zFar < zNear))
    return bad(std::string("declared ") + (cam.reversedZ ? "reversed-Z" : "standard depth") +
               ", but the orthographic projection maps the near plane to depth " + (cam.reversedZ ? "0" : "1"));
  if (!(zFar < 0)) return bad("orthographic far plane is not in front of the eye");
  m.nearDistance = -zNear;
  m.farDistance = -zFar;
  return Status::success();
}

double linearZ(const DepthModel& m, ProjectionKind kind, double d) {
  if (kind == ProjectionKind::Orthographic) return d * m.c1 + m.c2;
  return m.c0 / (d * m.c1 + m.c2);
}

namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

Status checkViewport(std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0 || width > kMaxImageSide || height > kMaxImageSide)
    return bad("viewport size is " + std::to_string(width) + "x" + std::to_string(height) +
               "; each side must be in [1, " + std::to_string(kMaxImageSide) + "]");
  return Status::success();
}

}  // namespace

Status checkPerspectiveArguments(double fovy, std::uint32_t width, std::uint32_t height, double n, double f) {
  if (!(fovy > 0 && fovy < std::numbers::pi))
    return bad("vertical field of view " + number(fovy) + " rad (" + number(fovy * 180 / std::numbers::pi) +
               " degrees) is outside (0, pi)");
  if (Status st = checkViewport(width, height); !st) return st;
  if (!(std::isfinite(n) && n > 0)) return bad("near distance " + number(n) + " must be finite and > 0");
  if (std::isnan(f) || f == -INFINITY) return bad("far distance " + number(f) + " must be a number > near or +inf");
  if (!(f > n))
    return bad("far distance " + number(f) + (f == n ? " equals" : " is nearer than") + " the near distance " +
               number(n) + ": far must be beyond near (or +inf)");
  return Status::success();
}

Status checkOrthographicArguments(double halfHeight, std::uint32_t width, std::uint32_t height, double n, double f) {
  if (!(std::isfinite(halfHeight) && halfHeight > 0))
    return bad("orthographic half height " + number(halfHeight) + " must be finite and > 0");
  if (Status st = checkViewport(width, height); !st) return st;
  if (!std::isfinite(n)) return bad("near distance " + number(n) + " must be finite");
  if (!std::isfinite(f)) return bad("far distance " + number(f) + " of an orthographic projection must be finite");
  if (!(f > n))
    return bad("far distance " + number(f) + (f == n ? " equals" : " is nearer than") + " the near distance " +
               number(n) + ": far must be beyond near");
  return Status::success();
}

Camera perspectiveCamera(double fovy, std::uint32_t width, std::uint32_t height, double n, double f, ClipDepth clip,
                         bool reversedZ) {
  Camera c;
  c.width = width;
  c.height = height;
  c.clipDepth = clip;
  c.reversedZ = reversedZ;
  c.infiniteFar = std::isinf(f);
  const double t = 1.0 / std::tan(fovy / 2.0);
  auto P = [&](int row, int col) -> double& { return c.projection[col * 4 + row]; };
  P(0, 0) = t * height / width;
  P(1, 1) = t;
  P(3, 2) = -1.0;
  // Choose ndc.z(z) so that the near plane lands on the near end of the clip range.
  const double ndcNear = reversedZ ? 1.0 : (clip == ClipDepth::ZeroToOne ? 0.0 : -1.0);
  const double ndcFar = reversedZ ? (clip == ClipDepth::ZeroToOne ? 0.0 : -1.0) : 1.0;
  // ndc.z = -C - D/z: at z=-n: -C + D/n = ndcNear; at z=-f: -C + D/f = ndcFar (D/f -> 0 when f = inf).
  if (c.infiniteFar) {
    P(2, 2) = -ndcFar;
    P(2, 3) = (ndcNear - ndcFar) * n;
  } else {
    P(2, 3) = (ndcNear - ndcFar) / (1.0 / n - 1.0 / f);
    P(2, 2) = -(ndcFar - P(2, 3) / f);
  }
  return c;
}

Camera orthographicCamera(double halfHeight, std::uint32_t width, std::uint32_t height, double n, double f,
                          ClipDepth clip, bool reversedZ) {
  Camera c;
  c.kind = ProjectionKind::Orthographic;
  c.width = width;
  c.height = height;
  c.clipDepth = clip;
  c.reversedZ = reversedZ;
  auto P = [&](int row, int col) -> double& { return c.projection[col * 4 + row]; };
  const double halfWidth = halfHeight * width / height;
  P(0, 0) = 1.0 / halfWidth;
  P(1, 1) = 1.0 / halfHeight;
  P(3, 3) = 1.0;
  const double ndcNear = reversedZ ? 1.0 : (clip == ClipDepth::ZeroToOne ? 0.0 : -1.0);
  const double ndcFar = reversedZ ? (clip == ClipDepth::ZeroToOne ? 0.0 : -1.0) : 1.0;
  // ndc.z = C*z + D with z=-n -> ndcNear, z=-f -> ndcFar.
  P(2, 2) = (ndcFar - ndcNear) / (n - f);
  P(2, 3) = ndcNear + P(2, 2) * n;
  return c;
}

}  // namespace sao
