#include "sao/samples/flip.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>

namespace sao::samples {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The paper's constants: colour exponent q_c, remap knee p_c and its target p_t, feature width
// w (degrees) and feature exponent q_f.
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95, kFeatureWidthDeg = 0.082, kQf = 0.5;
// The contrast sensitivity filters' Gaussian scales b (deg^2): achromatic b1; the largest of all
// three channels (blue-yellow's 0.04) sets the filter radius, as in the paper, so that the grey-only
// filter here has the same footprint as the full one.
constexpr double kAchromaticB1 = 0.0047, kLargestB = 0.04;
constexpr std::array<double, 3> kD65 = {0.950428545, 1.0, 1.088900371};  // XYZ white, Y = 1

double srgbToLinear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

double labF(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

// CIELAB of a linear sRGB colour with the Hunt adjustment (a*, b* scaled by L*/100).
std::array<double, 3> huntLab(double r, double g, double b) {
  const double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / kD65[0];
  const double y = (0.2126729 * r + 0.7151522 * g + 0.0721750 * b) / kD65[1];
  const double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / kD65[2];
  const double l = 116 * labF(y) - 16;
  return {l, 0.01 * l * 500 * (labF(x) - labF(y)), 0.01 * l * 200 * (labF(y) - labF(z))};
}

// Separable convolution with clamp-to-edge borders: `along` x (true) or y.
std::vector<double> convolve(const std::vector<double>& in, int w, int h, const std::vector<double>& kernel, bool alongX) {
  const int r = int(kernel.size() / 2);
  std::vector<double> out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int k = -r; k <= r; ++k) {
        const int xx = alongX ? std::clamp(x + k, 0, w - 1) : x, yy = alongX ? y : std::clamp(y + k, 0, h - 1);
        s += kernel[std::size_t(k + r)] * in[std::size_t(yy) * w + xx];
      }
      out[std::size_t(y) * w + x] = s;
    }
  return out;
}

// The achromatic CSF as a normalised 1D Gaussian in pixels.
std::vector<double> csfKernel(double ppd) {
  const int r = int(std::ceil(3 * std::sqrt(kLargestB / (2 * kPi * kPi)) * ppd));
  std::vector<double> k(std::size_t(2 * r + 1));
  double sum = 0;
  for (int i = -r; i <= r; ++i) {
    const double deg = i / ppd;
    sum += k[std::size_t(i + r)] = std::exp(-kPi * kPi * deg * deg / kAchromaticB1);
  }
  for (double& v : k) v /= sum;
  return k;
}

struct FeatureKernels {
  std::vector<double> gauss, edge, point;  // G normalised to 1; G' and G'' with positive / negative lobes each +-1
};

FeatureKernels featureKernels(double ppd) {
  const double sigma = 0.5 * kFeatureWidthDeg * ppd;
  const int r = int(std::ceil(3 * sigma));
  FeatureKernels f;
  double g = 0, ePos = 0, eNeg = 0, pPos = 0, pNeg = 0;
  for (int i = -r; i <= r; ++i) {
    const double gi = std::exp(-double(i) * i / (2 * sigma * sigma));
    const double ei = -i * gi, pi = (double(i) * i / (sigma * sigma) - 1) * gi;
    f.gauss.push_back(gi), f.edge.push_back(ei), f.point.push_back(pi);
    g += gi;
    (ei > 0 ? ePos : eNeg) += std::fabs(ei);
    (pi > 0 ? pPos : pNeg) += std::fabs(pi);
  }
  for (std::size_t i = 0; i < f.gauss.size(); ++i) {
    f.gauss[i] /= g;
    f.edge[i] /= f.edge[i] > 0 ? ePos : eNeg;
    f.point[i] /= f.point[i] > 0 ? pPos : pNeg;
  }
  return f;
}

struct Features {
  std::vector<double> edge, point;  // |gradient| and |second derivatives| per pixel
};

Features features(const std::vector<double>& luminance, int w, int h, const FeatureKernels& k) {
  const auto gx = convolve(luminance, w, h, k.gauss, true);
  const auto dx = convolve(convolve(luminance, w, h, k.edge, true), w, h, k.gauss, false);
  const auto ddx = convolve(convolve(luminance, w, h, k.point, true), w, h, k.gauss, false);
  const auto dy = convolve(gx, w, h, k.edge, false);
  const auto ddy = convolve(gx, w, h, k.point, false);
  Features f{std::vector<double>(luminance.size()), std::vector<double>(luminance.size())};
  for (std::size_t i = 0; i < luminance.size(); ++i) {
    f.edge[i] = std::hypot(dx[i], dy[i]);
    f.point[i] = std::hypot(ddx[i], ddy[i]);
  }
  return f;
}

}  // namespace

double flipMaxColorDistance() {
  const auto g = huntLab(0, 1, 0), b = huntLab(0, 0, 1);
  return std::pow(std::fabs(g[0] - b[0]) + std::hypot(g[1] - b[1], g[2] - b[2]), kQc);
}

FloatImage flipErrorMap(const FloatImage& test, const FloatImage& reference, double ppd) {
  if (test.extent.width != reference.extent.width || test.extent.height != reference.extent.height ||
      test.channels != 1 || reference.channels != 1)
    throw std::invalid_argument("flipErrorMap: two 1-channel images of one extent expected");
  if (!(ppd > 0)) throw std::invalid_argument("flipErrorMap: pixels per degree must be positive");
  const int w = int(test.extent.width), h = int(test.extent.height);
  const std::size_t n = std::size_t(w) * h;
  // Linear luminance of the grey pixels, which for a grey is also FLIP's normalised achromatic
  // channel (Y' + 16) / 116 with Y' = 116 Y - 16.
  std::vector<double> lt(n), lr(n);
  for (std::size_t i = 0; i < n; ++i) {
    lt[i] = srgbToLinear(std::clamp(double(test.data[i]), 0.0, 1.0));
    lr[i] = srgbToLinear(std::clamp(double(reference.data[i]), 0.0, 1.0));
  }
  // Colour term: filter Y' (affine in Y, so filtering Y is the same), back to linear, clamp, L*.
  const auto csf = csfKernel(ppd);
  const auto ft = convolve(convolve(lt, w, h, csf, true), w, h, csf, false);
  const auto fr = convolve(convolve(lr, w, h, csf, true), w, h, csf, false);
  const double cmax = flipMaxColorDistance(), knee = kPc * cmax;
  // Feature term on the unfiltered luminance.
  const FeatureKernels kernels = featureKernels(ppd);
  const Features et = features(lt, w, h, kernels), er = features(lr, w, h, kernels);
  FloatImage out(test.extent, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const double lStarT = 116 * labF(std::clamp(ft[i], 0.0, 1.0)) - 16;
    const double lStarR = 116 * labF(std::clamp(fr[i], 0.0, 1.0)) - 16;
    double color = std::pow(std::fabs(lStarT - lStarR), kQc);
    color = color < knee ? color * kPt / knee : kPt + (color - knee) / (cmax - knee) * (1 - kPt);
    const double feature = std::pow(
        std::max(std::fabs(et.edge[i] - er.edge[i]), std::fabs(et.point[i] - er.point[i])) / std::sqrt(2.0), kQf);
    out.data[i] = float(std::pow(color, 1 - feature));
  }
  return out;
}

double meanFlip(const FloatImage& test, const FloatImage& reference, const std::vector<unsigned char>& mask, double ppd) {
  if (mask.size() != test.data.size()) throw std::invalid_argument("meanFlip: the mask must have one entry per pixel");
  FloatImage t = test, r = reference;
  std::size_t pixels = 0;
  for (std::size_t i = 0; i < t.data.size(); ++i)
    if (mask[i]) ++pixels;
    else t.data[i] = r.data[i] = 1.0f;
  if (!pixels) return NAN;
  const FloatImage map = flipErrorMap(t, r, ppd);
  double sum = 0;
  for (std::size_t i = 0; i < map.data.size(); ++i)
    if (mask[i]) sum += map.data[i];
  return sum / double(pixels);
}

}  // namespace sao::samples
