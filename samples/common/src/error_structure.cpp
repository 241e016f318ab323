#include "sao/samples/error_structure.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>

namespace sao::samples {
namespace {

// Separable convolution with the truncated Gaussian, zero outside the image.
std::vector<double> gaussian(const std::vector<double>& in, std::uint32_t w, std::uint32_t h, double sigma) {
  const int R = int(std::ceil(3 * sigma));
  std::vector<double> k(std::size_t(2 * R + 1));
  for (int t = -R; t <= R; ++t) k[std::size_t(t + R)] = std::exp(-0.5 * t * t / (sigma * sigma));
  std::vector<double> tmp(in.size(), 0.0), out(in.size(), 0.0);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      double s = 0;
      for (int t = std::max(-R, -int(x)); t <= std::min(R, int(w - 1 - x)); ++t)
        s += k[std::size_t(t + R)] * in[std::size_t(y) * w + x + t];
      tmp[std::size_t(y) * w + x] = s;
    }
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      double s = 0;
      for (int t = std::max(-R, -int(y)); t <= std::min(R, int(h - 1 - y)); ++t)
        s += k[std::size_t(t + R)] * tmp[(std::size_t(y) + t) * w + x];
      out[std::size_t(y) * w + x] = s;
    }
  return out;
}

double rms(double sumSquares, std::size_t n) { return n ? std::sqrt(sumSquares / double(n)) : NAN; }

}  // namespace

std::vector<unsigned char> silhouetteBand(const FloatImage& positions, std::uint32_t g) {
  const std::uint32_t W = positions.extent.width, H = positions.extent.height;
  const Extent e{W - 2 * g, H - 2 * g};
  std::vector<unsigned char> edge(std::size_t(W) * H, 0);
  auto geometry = [&](std::uint32_t x, std::uint32_t y) { return positions.at(x, y, 3) != 0.0f; };
  auto jump = [&](std::uint32_t x0, std::uint32_t y0, std::uint32_t x1, std::uint32_t y1) {
    const bool a = geometry(x0, y0), b = geometry(x1, y1);
    if (a != b) return true;
    if (!a) return false;
    const double z0 = std::fabs(positions.at(x0, y0, 2)), z1 = std::fabs(positions.at(x1, y1, 2));
    return std::fabs(z0 - z1) > kDiscontinuityRelativeJump * std::min(z0, z1);
  };
  for (std::uint32_t y = 0; y < H; ++y)
    for (std::uint32_t x = 0; x < W; ++x) {
      if (x + 1 < W && jump(x, y, x + 1, y)) edge[std::size_t(y) * W + x] = edge[std::size_t(y) * W + x + 1] = 1;
      if (y + 1 < H && jump(x, y, x, y + 1)) edge[std::size_t(y) * W + x] = edge[std::size_t(y + 1) * W + x] = 1;
    }
  const int B = kSilhouetteBandPx;
  std::vector<unsigned char> band(std::size_t(e.width) * e.height, 0);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      bool near = false;
      for (int dy = -B; dy <= B && !near; ++dy)
        for (int dx = -B; dx <= B && !near; ++dx) {
          const std::int64_t sx = std::int64_t(x + g) + dx, sy = std::int64_t(y + g) + dy;
          if (dx * dx + dy * dy > B * B || sx < 0 || sy < 0 || sx >= W || sy >= H) continue;
          near = edge[std::size_t(sy) * W + std::size_t(sx)] != 0;
        }
      band[std::size_t(y) * e.width + x] = near;
    }
  return band;
}

ErrorStructure errorStructure(const FloatImage& ao, const FloatImage& reference, const std::vector<unsigned char>& mask,
                              const std::vector<unsigned char>& band) {
  ErrorStructure s;
  const std::uint32_t w = ao.extent.width, h = ao.extent.height;
  const std::size_t n = std::size_t(w) * h;
  if (reference.extent.width != w || reference.extent.height != h || ao.data.size() != n ||
      reference.data.size() != n || mask.size() != n || band.size() != n)
    return s;  // nothing comparable: every figure undefined
  std::vector<double> e(n, 0.0), m(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (mask[i]) e[i] = double(ao.data[i]) - double(reference.data[i]), m[i] = 1.0;
  const std::vector<double> num = gaussian(e, w, h, kBlotchSigmaPx), den = gaussian(m, w, h, kBlotchSigmaPx);
  double low = 0, high = 0, sil = 0;
  std::size_t pixels = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!mask[i]) continue;
    const double lp = num[i] / den[i];  // den >= G(0) > 0 at a mask pixel
    low += lp * lp;
    high += (e[i] - lp) * (e[i] - lp);
    ++pixels;
    if (band[i]) sil += e[i] * e[i], ++s.silhouettePixels;
  }
  s.blotchRmse = rms(low, pixels);
  s.highFrequencyRmse = rms(high, pixels);
  s.silhouetteRmse = rms(sil, s.silhouettePixels);
  return s;
}

Status writeErrorMapPng(const std::string& path, const FloatImage& ao, const FloatImage& reference,
                        const std::vector<unsigned char>& mask) {
  const Extent e = ao.extent;
  std::vector<unsigned char> px(std::size_t(e.width) * e.height * 3);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      const std::uint32_t row = e.height - 1 - y;  // row 0 of the images is the bottom of the screen
      const std::size_t i = std::size_t(row) * e.width + x;
      unsigned char* p = &px[(std::size_t(y) * e.width + x) * 3];
      if (!mask[i]) {
        p[0] = p[1] = p[2] = 128;
        continue;
      }
      const double t = std::clamp((double(ao.data[i]) - double(reference.data[i])) / kErrorMapScale, -1.0, 1.0);
      const auto fade = static_cast<unsigned char>(std::lround(255.0 * (1.0 - std::fabs(t))));
      p[0] = t < 0 ? fade : 255;  // negative: red and green fade, blue stays
      p[1] = fade;
      p[2] = t > 0 ? fade : 255;
    }
  if (!stbi_write_png(path.c_str(), int(e.width), int(e.height), 3, px.data(), int(e.width) * 3))
    return Status::error(StatusCode::IoError, "cannot write '" + path + "'");
  return Status::success();
}

}  // namespace sao::samples
