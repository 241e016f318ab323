#include "image_compare.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "sao/io.h"

namespace sao::test {

bool acceptable(const Agreement& a) { return a.fractionWithin >= 0.999 && a.beyond == 0 && a.nonFinite == 0; }

Agreement compare(const FloatImage& actual, const FloatImage& expected, std::uint32_t channel, double within,
                  double never, const std::string& failureDir, const std::string& name, std::string* note) {
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
  const std::size_t k = std::min(n - 1, std::size_t(std::ceil(0.999 * double(n))) - 1);
  std::nth_element(diffs.begin(), diffs.begin() + std::ptrdiff_t(k), diffs.end());
  a.p999 = diffs[k];
  if (!acceptable(a)) {
    std::error_code ec;
    std::filesystem::create_directories(failureDir, ec);
    const std::string base = failureDir + "/" + name;
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

}  // namespace sao::test
