// An engine with its own Vulkan renderer runs the effect from sao::core alone: it implements
// sao::Executor (images, pipelines from the installed .spv files, barriers, dispatches) and lets
// sao::FrameState decide the plan, the schedule, the parameter block and the history. Each depth
// file runs a few frames under the Khronos validation layer with synchronization validation, and
// its output is compared with the CPU reference. Only the installed sao::core, sao::io and
// sao::cpu and the system's Vulkan loader are used (no sao::vulkan), so it builds against a package.
// The engine itself is in vk_engine/ (its effect object, executor, device and transfers; the test
// suite's third executor, tests/executors/engine_executor.cpp, runs the same code); this file is
// the command-line program around it.
//
//   sao-example-vulkan-engine --shaders DIR [--frames N] [--set NAME=VALUE]... DEPTH.exr [...]
#include <vulkan/vulkan.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/cpu/reference.h"
#include "sao/image.h"
#include "sao/io.h"
#include "sao/settings.h"
#include "sao_effect.h"
#include "vk_engine/engine_bootstrap.h"
#include "vk_engine/engine_effect.h"
#include "vk_engine/engine_transfer.h"

namespace {

namespace gen = sao::gen;
using sao::Status;
using sao::StatusCode;
using sao::vkengine::EngineEffect;

// One depth file through the engine: its depth image, a configuration of its own (the history
// starts again), `frames` frames at frame index 0 (the spiral of the CPU reference's run), the
// output read back.
Status runFile(EngineEffect& effect, const sao::Settings& settings, std::uint32_t frames, const sao::DepthImage& depth,
               const sao::Camera& camera, sao::FloatImage& ao, std::size_t& passes) {
  sao::vkengine::Image depthImage;
  struct FreeDepth {
    EngineEffect& e;
    sao::vkengine::Image& i;
    ~FreeDepth() { i.destroy(e.device().device()); }
  } freeDepth{effect, depthImage};
  // D32F through the depth aspect, or LinearZ as R32F, left in SHADER_READ_ONLY_OPTIMAL.
  if (Status st = sao::vkengine::uploadDepth(effect.device(), depth, depthImage); !st) return st;
  sao::vkengine::EngineFrame frame;
  frame.inputs[std::size_t(gen::ResourceId::depth)] =
      sao::vkengine::inputOf(depthImage, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  if (Status st = effect.configure(settings, camera, frame); !st) return st;
  passes = effect.plan().passes.size();
  for (std::uint32_t f = 0; f < frames; ++f)
    if (Status st = effect.run(settings, camera, frame); !st)
      return Status::error(st.code, "frame " + std::to_string(f) + ": " + st.message);
  return effect.readOutput(ao);
}

// The GPU's output against the CPU reference in float (as a GPU computes); with the temporal
// setting the CPU runs as many frames, carrying the history from run to run as the GPU does.
bool compare(const std::string& path, const sao::Settings& settings, std::uint32_t frames, const sao::FloatImage& vk,
             std::size_t passes, const sao::DepthImage& depth, const sao::Camera& camera) {
  sao::cpu::Inputs in;
  in.depth = &depth;
  in.outputFormat = gen::Format::R16F;
  sao::cpu::Options options;
  options.precision = sao::cpu::Precision::Float;
  sao::cpu::Result cpu, previous;
  for (std::uint32_t f = 0; f < (settings.temporal ? frames : 1); ++f) {
    in.history = f ? &previous.images[std::size_t(gen::ResourceId::history)][0] : nullptr;
    in.previousCamera = f ? &camera : nullptr;
    if (Status st = sao::cpu::run(settings, camera, in, options, cpu); !st)
      return std::fprintf(stderr, "%s: the CPU reference failed: %s\n", path.c_str(), st.message.c_str()), false;
    std::swap(cpu, previous);
  }
  const sao::FloatImage& ref = previous.ao;
  if (ref.extent != vk.extent || ref.channels != 1)
    return std::fprintf(stderr, "%s: the CPU reference's output differs in size\n", path.c_str()), false;
  std::vector<float> diff(vk.data.size());
  std::size_t nonFinite = 0, above = 0;
  for (std::size_t i = 0; i < diff.size(); ++i) {
    const bool finite = std::isfinite(vk.data[i]) && std::isfinite(ref.data[i]);
    diff[i] = finite ? std::fabs(vk.data[i] - ref.data[i]) : INFINITY;
    nonFinite += !finite;
    above += diff[i] > 2.0f / 255.0f;
  }
  std::sort(diff.begin(), diff.end());
  const float max = diff.back(), p999 = diff[std::size_t(std::ceil(0.999 * double(diff.size()))) - 1];
  std::printf("%s: %ux%u, %zu passes, max |vk - cpu| = %.3g (%.3f/255), p99.9 = %.3f/255, %zu texels > 2/255\n",
              path.c_str(), vk.extent.width, vk.extent.height, passes, max, max * 255.0f, p999 * 255.0f, above);
  if (nonFinite) std::fprintf(stderr, "%s: %zu texels are not finite\n", path.c_str(), nonFinite);
  if (p999 > 2.0f / 255.0f) std::fprintf(stderr, "%s: p99.9 exceeds 2/255\n", path.c_str());
  return nonFinite == 0 && p999 <= 2.0f / 255.0f;
}

// A depth file this engine takes: a sao.* camera, single-sampled D32F or LinearZ, valid texels.
Status readDepth(const std::string& path, sao::DepthImage& depth, sao::Camera& camera) {
  bool hasCamera = false;
  if (Status st = sao::readDepthExr(path, depth, camera, hasCamera); !st) return st;  // it names the file
  if (!hasCamera)
    return Status::error(StatusCode::InvalidInput, path + " has no sao.* camera (sao-render --save-depth writes one)");
  if (depth.samples > 1)
    return Status::error(StatusCode::UnsupportedFormat, path + " is multisampled (" + std::to_string(depth.samples) +
                                                        " samples); this engine reads single-sampled depth");
  if (depth.format != sao::DepthFormat::D32F && depth.format != sao::DepthFormat::LinearZ)
    return Status::error(StatusCode::UnsupportedFormat,
                         path + " holds " + sao::toString(depth.format) + " depth; this engine takes D32F or LinearZ");
  // Temporal accumulation needs the view matrix: a file without one is a camera that never moves.
  if (!camera.view) camera.view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (Status st = sao::checkDepthValues(depth); !st) return Status::error(st.code, path + ": " + st.message);
  return Status::success();
}

int usage(const char* message) {
  std::fprintf(stderr,
               "sao-example-vulkan-engine: %s\n"
               "usage: sao-example-vulkan-engine --shaders DIR [--frames N] [--set NAME=VALUE]... [--no-validation]\n"
               "                                 DEPTH.exr [DEPTH.exr ...]\n"
               "  --shaders DIR     the installed shader files, <fileStem>.spv\n"
               "  --frames N        frames per depth file, 1..1000 (default 2)\n"
               "  --set NAME=VALUE  a setting (default: the settings' defaults)\n"
               "  --no-validation   without VK_LAYER_KHRONOS_validation (required by default)\n",
               message);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string shaders;
  std::uint32_t frames = 2;
  sao::Settings settings;
  bool validation = true;
  std::vector<std::string> files;
  std::vector<sao::SettingId> given;  // a setting given that has no effect is refused
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--shaders" || a == "--frames" || a == "--set") && i + 1 == argc)
      return usage((a + " needs a value").c_str());
    if (a == "--shaders") {
      shaders = argv[++i];
    } else if (a == "--frames") {
      char* end = nullptr;
      const unsigned long n = std::strtoul(argv[++i], &end, 10);
      if (*end || argv[i][0] == '-' || n < 1 || n > 1000) return usage("--frames takes 1..1000");
      frames = std::uint32_t(n);
    } else if (a == "--set") {
      const std::string assignment = argv[++i];
      if (Status st = sao::setFromAssignment(settings, assignment); !st) return usage(st.message.c_str());
      if (const auto id = sao::findSetting(assignment.substr(0, assignment.find('=')))) given.push_back(*id);
    } else if (a == "--no-validation") {
      validation = false;
    } else if (a == "--help") {
      return usage("the effect run by an engine's own sao::Executor on Vulkan"), 0;
    } else if (a.rfind("--", 0) == 0) {
      return usage(("unknown option " + a).c_str());
    } else {
      files.push_back(a);
    }
  }
  if (shaders.empty()) return usage("--shaders DIR is required");
  if (files.empty()) return usage("no depth file given");
  for (sao::SettingId id : given)
    if (const gen::InertRule* rule = sao::inertRule(settings, id)) return usage(sao::describeInert(*rule).c_str());

  // Every file read and checked before the device starts.
  std::vector<sao::DepthImage> depths(files.size());
  std::vector<sao::Camera> cameras(files.size());
  for (std::size_t i = 0; i < files.size(); ++i)
    if (Status st = readDepth(files[i], depths[i], cameras[i]); !st)
      return std::fprintf(stderr, "sao-example-vulkan-engine: %s\n", st.message.c_str()), 1;

  int failed = 0;
  int validationMessages = 0;
  {
    std::unique_ptr<sao::vkengine::Bootstrap> gpu;
    if (Status st = sao::vkengine::Bootstrap::create(validation, validationMessages, gpu); !st)
      return std::fprintf(stderr, "sao-example-vulkan-engine: %s\n", st.message.c_str()), 1;
    std::unique_ptr<EngineEffect> effect;  // one effect instance, configured for each file
    if (Status st = EngineEffect::create(gpu->handles(), shaders, effect); !st)
      return std::fprintf(stderr, "executor: %s\n", st.message.c_str()), 1;
    for (std::size_t i = 0; i < files.size(); ++i) {
      sao::FloatImage ao;
      std::size_t passes = 0;
      if (Status st = runFile(*effect, settings, frames, depths[i], cameras[i], ao, passes); !st)
        std::fprintf(stderr, "%s: %s\n", files[i].c_str(), st.message.c_str()), ++failed;
      else if (!compare(files[i], settings, frames, ao, passes, depths[i], cameras[i]))
        ++failed;
    }
  }  // the effect, then the device and the instance: the layer reports leaks here
  if (validation) std::printf("validation: %d message(s)\n", validationMessages);
  if (failed) std::fprintf(stderr, "%d of %zu file(s) failed\n", failed, files.size());
  return failed || validationMessages ? 1 : 0;
}
