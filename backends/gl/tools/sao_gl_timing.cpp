// sao-gl-timing: per-pass time of the OpenGL backend (or, with --api gles / both, the OpenGL ES 3.1
// backend on an ES context) at 1280x720 and 1920x1080 (or the sizes given), median of N runs per
// preset, and each plan's bytes, on a headless EGL context. A measurement tool, not a test.
// `sao-gl-timing --help` lists the options.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "sao/cli/command_line.h"
#include "sao/cli/shared_options.h"
#include "sao/gl/effect.h"
#include "sao/gl/headless.h"
#include "sao/gles/effect.h"
#include "sao/presets.h"

namespace {

// A floor, a back wall and a row of spheres: enough depth variety for every MIP level to be used.
float sceneDepth(const sao::Camera& cam, const sao::DepthModel& model, std::uint32_t x, std::uint32_t y) {
  const double W = cam.width, H = cam.height, g = cam.guardBand;
  const double nx = 2.0 * (x - g + 0.5) / W - 1.0, ny = 2.0 * (y - g + 0.5) / H - 1.0;
  const double dx = nx / cam.projection[0], dy = ny / cam.projection[5], dz = -1.0;  // view ray (eye at 0)
  double best = 1e30;
  if (dy < 0) best = std::min(best, -1.0 / dy);           // floor y = -1
  best = std::min(best, 12.0);                            // wall z = -12
  for (int i = -3; i <= 3; ++i) {                         // spheres r 0.6 at (1.5 i, -0.4, -5)
    const double c[3] = {1.5 * i, -0.4, -5.0}, r = 0.6;
    const double b = dx * c[0] + dy * c[1] + dz * c[2], a = dx * dx + dy * dy + dz * dz;
    const double cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2] - r * r, disc = b * b - a * cc;
    if (disc > 0) best = std::min(best, (b - std::sqrt(disc)) / a);
  }
  const double z = -best;  // t with dz = -1 is the distance along -z
  // Standard OpenGL depth: d = (c0 / z - c2) / c1 from z = c0 / (d c1 + c2).
  return float((model.c0 / z - model.c2) / model.c1);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The plan's image bytes as the API allocates them: on ES each image in the format the effect's
// `target gles` rule gives it (rg16f intermediates take rgba16f, ...).
std::uint64_t allocatedBytes(const sao::Plan& plan, bool es) {
  if (!es) return plan.totalBytes;
  std::uint64_t total = 0;
  for (const sao::PlannedImage& img : plan.images)
    total += img.bytes / sao::bytesPerTexel(img.format) * sao::bytesPerTexel(sao::gen::glesStorageFormat(img.format));
  return total;
}

struct Options {
  std::uint32_t runs = 7, guard = 16;
  std::vector<sao::Preset> presets;
  std::vector<sao::Extent> sizes;
};

// Every size and preset on one API's effect, in the current context.
template <typename Effect, typename Inputs>
int measure(const char* api, Effect& effect, const Options& o) {
  const bool es = std::string(api) == "gles";
  for (const auto [w, h] : o.sizes) {
    sao::Camera cam = sao::perspectiveCamera(std::numbers::pi / 3.0, w, h, 0.1, 100.0,
                                             sao::ClipDepth::NegativeOneToOne, false);
    cam.guardBand = o.guard;
    sao::DepthModel model;
    if (sao::Status st = sao::analyze(cam, model); !st) {
      std::fprintf(stderr, "sao-gl-timing: %s\n", st.message.c_str());
      return 1;
    }
    const std::uint32_t dw = w + 2 * o.guard, dh = h + 2 * o.guard;
    std::vector<float> depth(std::size_t(dw) * dh);
    for (std::uint32_t y = 0; y < dh; ++y)
      for (std::uint32_t x = 0; x < dw; ++x) depth[std::size_t(y) * dw + x] = sceneDepth(cam, model, x, y);
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, GLsizei(dw), GLsizei(dh));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, GLsizei(dw), GLsizei(dh), GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    glBindTexture(GL_TEXTURE_2D, 0);

    for (sao::Preset preset : o.presets) {
      const sao::Settings settings = sao::presetSettings(preset);
      Inputs in;
      in.depth = {tex, sao::gl::kDepthComponent32F};
      // Warm-up: compiles the programs and allocates the images.
      if (sao::Status st = effect.render(cam, settings, in, {true}); !st) {
        std::fprintf(stderr, "sao-gl-timing: %s\n", st.message.c_str());
        return 1;
      }
      std::map<std::string, std::vector<double>> perPass;
      std::vector<std::string> order;
      std::vector<double> totals;
      sao::TimingMethod method = sao::TimingMethod::None;
      for (std::uint32_t r = 0; r < o.runs; ++r) {
        if (sao::Status st = effect.render(cam, settings, in, {true}); !st) {
          std::fprintf(stderr, "sao-gl-timing: %s\n", st.message.c_str());
          return 1;
        }
        const sao::Timings& t = effect.timings();
        method = t.method;
        for (const auto& p : t.passes) {
          if (!perPass.count(p.pass)) order.push_back(p.pass);
          perPass[p.pass].push_back(p.milliseconds);
        }
        totals.push_back(t.totalMilliseconds());
      }
      std::string name;
      for (const auto& p : sao::presets())
        if (p.preset == preset) name = std::string(p.name);
      std::printf("\n%s %ux%u preset %-9s (%d taps, blur radius %d, csz levels %u) method: %s, plan %.2f MB\n", api, w, h,
                  name.c_str(), settings.samples, settings.blur_radius, effect.plan().cszLevels, sao::toString(method),
                  double(allocatedBytes(effect.plan(), es)) / 1e6);
      for (const auto& pass : order) {
        const auto& v = perPass[pass];
        std::printf("  %-10s median %9.3f ms   min %9.3f ms\n", pass.c_str(), median(v),
                    *std::min_element(v.begin(), v.end()));
      }
      std::printf("  %-10s median %9.3f ms   min %9.3f ms\n", "total", median(totals),
                  *std::min_element(totals.begin(), totals.end()));
    }
    glDeleteTextures(1, &tex);
  }
  return 0;
}

// One API: its context (GL 4.3 core or ES 3.1), its effect, every configuration.
template <typename Effect, typename Inputs>
int run(const char* api, bool es, const Options& o) {
  std::unique_ptr<sao::gl::HeadlessContext> ctx;
  sao::gl::HeadlessOptions ho;
  ho.debug = false;
  if (es) {
    ho.es = true;
    ho.major = 3;
    ho.minor = 1;
  }
  if (sao::Status st = sao::gl::HeadlessContext::create(ctx, ho); !st) {
    std::fprintf(stderr, "sao-gl-timing: %s\n", st.message.c_str());
    return 1;
  }
  std::unique_ptr<Effect> effect;
  if (sao::Status st = Effect::create(sao::gl::HeadlessContext::getProcAddress(), effect); !st) {
    std::fprintf(stderr, "sao-gl-timing: %s\n", st.message.c_str());
    return 1;
  }
  std::printf("%s context: %s\nruns per configuration: %u (median reported), depth GL_DEPTH_COMPONENT32F, guard band %u\n",
              api, ctx->description().c_str(), o.runs, o.guard);
  return measure<Effect, Inputs>(api, *effect, o);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  std::string api = "gl";
  sao::cli::CommandLine cl("sao-gl-timing",
                           "Per-pass time of the OpenGL (or OpenGL ES 3.1) backend on a headless EGL context: the\n"
                           "median of N runs per preset and size, and each plan's bytes (a measurement tool, not a test).");
  sao::cli::addRuns(cl, o.runs, 5, "measured runs per configuration", "default 7; the median is reported");
  sao::cli::addPresetList(cl, o.presets);
  sao::cli::addImageSizes(cl, o.sizes, "an AO size to measure", "default: 1280x720 and 1920x1080");
  sao::cli::addGuardBand(cl, o.guard, "guard band in pixels on each side", "default 16");
  cl.choice("--api", api,
            [](const std::string& v) { return v == "gl" || v == "gles" || v == "both" ? std::optional(v) : std::nullopt; },
            "gl, gles or both", "API", "gl (OpenGL 4.3, sao::gl; the default), gles (OpenGL ES 3.1, sao::gles) or both, in one run");
  cl.parse(argc, argv);
  if (o.sizes.empty()) o.sizes = {{1280, 720}, {1920, 1080}};
  if (o.presets.empty())
    for (const auto& p : sao::presets()) o.presets.push_back(p.preset);
  if (api != "gles")
    if (const int rc = run<sao::gl::Effect, sao::gl::Inputs>("gl", false, o); rc) return rc;
  if (api != "gl") return run<sao::gles::Effect, sao::gles::Inputs>("gles", true, o);
  return 0;
}
