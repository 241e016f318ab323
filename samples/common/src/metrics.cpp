#include "sao/samples/metrics.h"

#include <cmath>

#include "sao/samples/flip.h"

namespace sao::samples {
namespace {

ErrorMetrics measure(const FloatImage& ao, const FloatImage& ref, const std::vector<unsigned char>& mask, double k) {
  ErrorMetrics m;
  const Extent e = ao.extent;
  auto value = [&](std::uint32_t x, std::uint32_t y) { return 1.0 - k * (1.0 - double(ao.at(x, y))); };
  double sq = 0, bias = 0, openDark = 0;
  std::size_t over = 0, openUnder = 0;
  bool aoConstant = true, refConstant = true;  // over the mask
  double aoFirst = 0, refFirst = 0;
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      if (!mask[std::size_t(y) * e.width + x]) continue;
      if (!m.pixels) aoFirst = value(x, y), refFirst = ref.at(x, y);
      aoConstant = aoConstant && value(x, y) == aoFirst;
      refConstant = refConstant && ref.at(x, y) == refFirst;
      const double d = value(x, y) - ref.at(x, y);
      sq += d * d;
      bias += d;
      over += std::fabs(d) > 0.1;
      if (ref.at(x, y) == 1.0f) {
        ++m.openPixels;
        openDark += 1.0 - value(x, y);
        openUnder += value(x, y) < 0.9;
      }
      ++m.pixels;
    }
  if (!m.pixels) return m;
  m.rmse = std::sqrt(sq / m.pixels);
  m.meanBias = bias / m.pixels;
  m.fractionOver01 = double(over) / m.pixels;
  if (m.openPixels) {
    m.openDarkening = openDark / double(m.openPixels);
    m.openShareUnder09 = double(openUnder) / double(m.openPixels);
  }
  // SSIM (Wang et al. 2004) on 8x8 windows with stride 4, constants for a data range of 1.
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  double ssimSum = 0;
  std::size_t windows = 0;
  for (std::uint32_t y0 = 0; y0 + 8 <= e.height; y0 += 4)
    for (std::uint32_t x0 = 0; x0 + 8 <= e.width; x0 += 4) {
      bool inside = true;
      double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      for (std::uint32_t y = y0; y < y0 + 8 && inside; ++y)
        for (std::uint32_t x = x0; x < x0 + 8; ++x) {
          if (!mask[std::size_t(y) * e.width + x]) {
            inside = false;
            break;
          }
          const double a = value(x, y), b = ref.at(x, y);
          sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
        }
      if (!inside) continue;
      const double n = 64, ma = sa / n, mb = sb / n;
      const double va = saa / n - ma * ma, vb = sbb / n - mb * mb, cov = sab / n - ma * mb;
      ssimSum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++windows;
    }
  m.ssim = windows && !(aoConstant && refConstant) ? ssimSum / windows : NAN;  // undefined: see metrics.h
  FloatImage scaled(e, 1);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) scaled.at(x, y) = float(value(x, y));
  m.flip = meanFlip(scaled, ref, mask);
  return m;
}

}  // namespace

std::vector<unsigned char> geometryMask(const FloatImage& positions, std::uint32_t g) {
  const Extent e{positions.extent.width - 2 * g, positions.extent.height - 2 * g};
  std::vector<unsigned char> mask(std::size_t(e.width) * e.height);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) mask[std::size_t(y) * e.width + x] = positions.at(x + g, y + g, 3) != 0.0f;
  return mask;
}

ReferenceComparison compareToReference(const FloatImage& ao, const FloatImage& ref, const std::vector<unsigned char>& mask) {
  ReferenceComparison c;
  c.raw = measure(ao, ref, mask, 1.0);
  double num = 0, den = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    const double oa = 1.0 - ao.data[i], orf = 1.0 - ref.data[i];
    num += oa * orf;
    den += oa * oa;
  }
  c.fittedIntensity = den > 0 ? num / den : NAN;  // den = 0: no occlusion in the AO, every k fits alike
  c.fitted = measure(ao, ref, mask, isDefined(c.fittedIntensity) ? c.fittedIntensity : 1.0);
  return c;
}

}  // namespace sao::samples
