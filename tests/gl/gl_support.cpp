#include "gl_support.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "sao/io.h"

namespace sao::gltest {

std::uint32_t uploadDepth(const DepthImage& depth, GlDepth format) {
  std::uint32_t t = 0;
  const Status st = gl::uploadDepth(depth, format, t);
  EXPECT_TRUE(st.ok()) << st.message;
  return t;
}

std::uint32_t uploadNormals(const FloatImage& normals) {
  std::uint32_t t = 0;
  const Status st = gl::uploadNormals(normals, t);
  EXPECT_TRUE(st.ok()) << st.message;
  return t;
}


gl::HeadlessContext& context() {
  static std::unique_ptr<gl::HeadlessContext> ctx = [] {
    std::unique_ptr<gl::HeadlessContext> c;
    const Status st = gl::HeadlessContext::create(c);
    if (!st) {
      std::fprintf(stderr, "no headless GL context: %s\n", st.message.c_str());
      std::abort();
    }
    std::printf("GL context: %s\n", c->description().c_str());
    return c;
  }();
  return *ctx;
}

void GlTest::SetUp() { context().clearMessages(); }

void GlTest::TearDown() {
  for (const auto& m : context().errors()) ADD_FAILURE() << "GL debug message: " << gl::HeadlessContext::format(m);
  context().clearMessages();
}

std::unique_ptr<gl::Effect> GlTest::makeEffect() {
  std::unique_ptr<gl::Effect> e;
  const Status st = gl::Effect::create(gl::HeadlessContext::getProcAddress(), e);
  EXPECT_TRUE(st.ok()) << st.message;
  return e;
}

Camera camera(std::uint32_t width, std::uint32_t height, std::uint32_t guard, double farDistance, bool reversedZ) {
  Camera c = perspectiveCamera(std::numbers::pi / 3.0, width, height, 0.1, farDistance, ClipDepth::NegativeOneToOne,
                               reversedZ);
  c.guardBand = guard;
  return c;
}

std::string failureDir() { return SAO_GL_TEST_FAILURE_DIR; }

bool acceptable(const Agreement& a) { return a.fractionWithin >= 0.999 && a.beyond == 0 && a.nonFinite == 0; }

Agreement compare(const FloatImage& actual, const FloatImage& expected, std::uint32_t channel, double within,
                  double never, const std::string& name, std::string* note) {
  Agreement a;
  if (actual.extent != expected.extent || channel >= actual.channels || channel >= expected.channels) {
    ADD_FAILURE() << name << ": images differ in size or channels";
    a.beyond = 1;
    return a;
  }
  const Extent e = actual.extent;
  const std::size_t n = std::size_t(e.width) * e.height;
  std::vector<double> diffs(n);
  FloatImage a1(e, 1), b1(e, 1), d1(e, 1);
  std::size_t ok = 0;
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      const float u = actual.at(x, y, channel), v = expected.at(x, y, channel);
      const double d = std::isfinite(u) ? std::fabs(double(u) - double(v)) : INFINITY;
      if (!std::isfinite(u)) ++a.nonFinite;
      diffs[std::size_t(y) * e.width + x] = d;
      a.maxAbs = std::max(a.maxAbs, d);
      ok += d <= within;
      a.beyond += d > never;
      a1.at(x, y) = std::isfinite(u) ? u : 0.0f;
      b1.at(x, y) = v;
      d1.at(x, y) = float(std::min(1.0, d / never));
    }
  a.fractionWithin = double(ok) / double(n);
  std::vector<double> sorted = diffs;
  const std::size_t k = std::min(n - 1, std::size_t(std::ceil(0.999 * double(n))) - 1);
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
  a.p999 = sorted[k];
  if (!acceptable(a)) {
    std::error_code ec;
    std::filesystem::create_directories(failureDir(), ec);
    const std::string base = failureDir() + "/" + name;
    (void)writeAoPng(base + "_actual.png", a1);
    (void)writeAoPng(base + "_expected.png", b1);
    (void)writeAoPng(base + "_diff.png", d1);
    (void)writeFloatExr(base + "_actual.exr", a1, {"A"});
    (void)writeFloatExr(base + "_expected.exr", b1, {"A"});
    if (note) {
      char white[32];
      std::snprintf(white, sizeof white, "%.3g/255", never * 255.0);
      *note = "images written to " + base + "_{actual,expected,diff}.png and _{actual,expected}.exr (diff: white = " +
              white + ")";
    }
  }
  return a;
}

}  // namespace sao::gltest
