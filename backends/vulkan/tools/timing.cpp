// sao-vk-timing: per-pass GPU time of the Vulkan backend at 1280x720 and 1920x1080 (or the sizes
// given), for every preset (or the ones given), median of N runs after one warm-up. Timestamps where
// the queue has them, else the fence fallback; the method used is printed. No validation layers.
// `sao-vk-timing --help` lists the options.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "sao/cli/command_line.h"
#include "sao/cli/shared_options.h"
#include "sao/presets.h"
#include "sao/vulkan/effect.h"
#include "sao/vulkan/headless.h"

namespace {

// A deterministic test scene: a ground plane, a back wall and a few spheres, ray-cast for a
// perspective camera with 60 degrees vertical field of view (depth 0..1, Vulkan convention).
sao::DepthImage scene(const sao::Camera& cam, sao::DepthFormat format) {
  sao::DepthModel model;
  (void)sao::analyze(cam, model);
  const std::uint32_t W = cam.width + 2 * cam.guardBand, H = cam.height + 2 * cam.guardBand;
  sao::DepthImage d;
  d.extent = {W, H};
  d.format = format;
  d.texels.resize(std::size_t(W) * H);
  const double p00 = cam.projection[0], p11 = cam.projection[5];
  const double A = cam.projection[10], B = cam.projection[14];  // clip z = A z + B, clip w = -z
  struct Sphere { double x, y, z, r; };
  const Sphere spheres[] = {{-1.2, -0.6, -5.0, 0.8}, {0.9, -0.9, -4.0, 0.5}, {0.2, -1.0, -7.0, 1.2}, {2.2, -0.7, -6.0, 0.7}};
  for (std::uint32_t y = 0; y < H; ++y)
    for (std::uint32_t x = 0; x < W; ++x) {
      // Ray through the texel centre (row 0 at ndc.y = -1).
      const double nx = ((x + 0.5 - cam.guardBand) / cam.width) * 2.0 - 1.0;
      const double ny = ((y + 0.5 - cam.guardBand) / cam.height) * 2.0 - 1.0;
      const double dx = nx / p00, dy = ny / p11, dz = -1.0;  // z = -1 plane
      double t = INFINITY;
      if (dy < 0) t = std::min(t, -1.5 / dy);  // ground y = -1.5
      t = std::min(t, 12.0);                  // back wall z = -12
      for (const auto& s : spheres) {
        const double ox = -s.x, oy = -s.y, oz = -s.z;
        const double a = dx * dx + dy * dy + dz * dz, b = 2 * (ox * dx + oy * dy + oz * dz);
        const double c = ox * ox + oy * oy + oz * oz - s.r * s.r, disc = b * b - 4 * a * c;
        if (disc >= 0) {
          const double t0 = (-b - std::sqrt(disc)) / (2 * a);
          if (t0 > 0) t = std::min(t, t0);
        }
      }
      const double z = -t;  // view-space z of the hit (dz = -1)
      const double depth = (A * z + B) / -z;
      d.texels[std::size_t(y) * W + x] = sao::encodeDepth(format, depth);
    }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  std::uint32_t runs = 7;
  bool fence = false;
  sao::DepthFormat format = sao::DepthFormat::D32F;
  std::vector<sao::Preset> presets;
  std::vector<sao::Extent> sizes;
  sao::cli::CommandLine cl("sao-vk-timing",
                           "Per-pass GPU time of the Vulkan backend: the median of N runs after one warm-up, per\n"
                           "preset and size; timestamps where the queue has them, else the fence fallback (the\n"
                           "method used is printed). No validation layers.");
  sao::cli::addRuns(cl, runs, 5, "measured runs per configuration", "default 7; the median is reported");
  sao::cli::addPresetList(cl, presets);
  sao::cli::addImageSizes(cl, sizes, "an AO size to measure", "default: 1280x720 and 1920x1080");
  cl.flag("--fence", fence, "time with the fence fallback even where the queue has timestamps");
  sao::cli::addDepthFormat(cl, "--format", format, "the depth format: D16 | D24 | D32F (default D32F)");
  cl.parse(argc, argv);
  if (presets.empty())
    for (const auto& p : sao::presets()) presets.push_back(p.preset);
  if (sizes.empty()) sizes = {{1280, 720}, {1920, 1080}};

  std::unique_ptr<sao::vk::headless::Context> ctx;
  if (auto st = sao::vk::headless::Context::create({}, ctx); !st) {
    std::fprintf(stderr, "headless Vulkan: %s\n", st.message.c_str());
    return 1;
  }
  std::printf("device: %s\n", ctx->description().c_str());
  std::printf("runs: median of %u (after 1 warm-up), depth %s\n", runs, sao::toString(format));

  for (const auto size : sizes) {
    sao::Camera cam = sao::perspectiveCamera(std::numbers::pi / 3.0, size.width, size.height, 0.1, 100.0,
                                             sao::ClipDepth::ZeroToOne, false);
    const sao::DepthImage depth = scene(cam, format);
    sao::vk::headless::Image depthImage;
    if (auto st = ctx->uploadDepth(depth, sao::vk::depthVkFormat(format), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depthImage); !st) {
      std::fprintf(stderr, "upload: %s\n", st.message.c_str());
      return 1;
    }
    for (const auto preset : presets) {
      const sao::Settings settings = sao::presetSettings(preset);
      std::unique_ptr<sao::vk::Effect> effect;
      if (auto st = sao::vk::Effect::create(ctx->deviceContext(), {}, effect); !st) {
        std::fprintf(stderr, "create: %s\n", st.message.c_str());
        return 1;
      }
      sao::vk::Inputs in;
      in.depth = {depthImage.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, sao::vk::depthVkFormat(format)};
      std::map<std::string, std::vector<double>> perPass;
      std::vector<std::string> order;
      std::vector<double> totals;
      sao::TimingMethod method = sao::TimingMethod::None;
      for (std::uint32_t r = 0; r <= runs; ++r) {
        sao::Timings t;
        if (auto st = effect->measure(ctx->queue(), cam, settings, in, nullptr, t,
                                      fence ? sao::vk::MeasureMethod::FenceClock : sao::vk::MeasureMethod::Auto);
            !st) {
          std::fprintf(stderr, "measure: %s\n", st.message.c_str());
          return 1;
        }
        if (r == 0) continue;  // warm-up
        method = t.method;
        for (const auto& p : t.passes) {
          if (!perPass.count(p.pass)) order.push_back(p.pass);
          perPass[p.pass].push_back(p.milliseconds);
        }
        totals.push_back(t.totalMilliseconds());
      }
      auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
      };
      std::printf("\n%ux%u preset %-9s (%s; csz levels %u)\n", size.width, size.height,
                  std::string(sao::presets()[static_cast<std::size_t>(preset)].name).c_str(), sao::toString(method),
                  effect->plan().cszLevels);
      for (const auto& name : order) std::printf("  %-10s %9.3f ms\n", name.c_str(), median(perPass[name]));
      std::printf("  %-10s %9.3f ms\n", "total", median(totals));
    }
    ctx->destroy(depthImage);
  }
  return 0;
}
