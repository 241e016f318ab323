#include "harness.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "harness_apis.h"

namespace sao::exectest {

const char* toString(Api api) {
  switch (api) {
    case Api::Gl: return "gl";
    case Api::Vulkan: return "vulkan";
    case Api::Engine: return "engine";
    case Api::Gles: return "gles";
  }
  return "?";
}

std::vector<Api> libraryApis() {
  std::vector<Api> v;
#if SAO_HARNESS_GL
  v.push_back(Api::Gl);
#endif
#if SAO_HARNESS_VULKAN
  v.push_back(Api::Vulkan);
#endif
  return v;
}

const char* describe(Feature feature) {
  switch (feature) {
    case Feature::OutputContents: return "an output whose texels the frame keeps (initial contents, a channel mask, a blend)";
    case Feature::MultisampledDepth: return "a multisampled depth";
    case Feature::Stereo: return "stereo layers (Frame::depthLayers)";
    case Feature::LibraryAllocations: return "counting the per-frame call's allocations in a library of its own";
  }
  return "?";
}

// The engine-side example implements none of the features (tests/executors/engine_executor.cpp);
// sao::gles reads no multisampled depth and no array layer (sao/gles/effect.h). Library allocations
// are counted in libsao_gles as in libsao_gl (api_allocations.h).
bool supports(Api api, Feature feature) {
  if (api == Api::Engine) return false;
  return api != Api::Gles || (feature != Feature::MultisampledDepth && feature != Feature::Stereo);
}

bool refusesOutput(Api api, gen::Format format) { return api == Api::Gles && gen::glesRefuses(format); }

const char* toString(Depth format) {
  switch (format) {
    case Depth::D16: return "D16";
    case Depth::D24: return "D24";
    case Depth::D24S8: return "D24S8";
    case Depth::D32F: return "D32F";
    case Depth::D32FS8: return "D32FS8";
    case Depth::R32F: return "R32F";
  }
  return "?";
}

DepthFormat cpuFormat(Depth format) {
  switch (format) {
    case Depth::D16: return DepthFormat::D16;
    case Depth::D24:
    case Depth::D24S8: return DepthFormat::D24;
    case Depth::D32F:
    case Depth::D32FS8: return DepthFormat::D32F;
    case Depth::R32F: return DepthFormat::LinearZ;
  }
  return DepthFormat::D32F;
}

Status Executor::render(const Frame& frame) {
  if (Status st = upload(frame); !st) return st;
  return run(frame);
}

std::unique_ptr<Executor> makeExecutor(Api api) {
#if SAO_HARNESS_GL
  if (api == Api::Gl) return makeGlExecutor();
#endif
#if SAO_HARNESS_VULKAN
  if (api == Api::Vulkan) return makeVkExecutor();
#endif
#if SAO_HARNESS_ENGINE
  if (api == Api::Engine) return makeEngineExecutor();
#endif
#if SAO_HARNESS_GLES
  if (api == Api::Gles) return makeGlesExecutor();
#endif
  ADD_FAILURE() << toString(api) << " is not built into this test program";
  return nullptr;
}

void checkMessagesBefore(Api api) {
#if SAO_HARNESS_GL
  if (api == Api::Gl) glMessagesBefore();
#endif
#if SAO_HARNESS_VULKAN
  // The engine-side example runs on the Vulkan test context: its messages are that context's.
  if (api == Api::Vulkan || api == Api::Engine) vkMessagesBefore();
#endif
#if SAO_HARNESS_GLES
  if (api == Api::Gles) glesMessagesBefore();
#endif
}

void checkMessagesAfter(Api api) {
#if SAO_HARNESS_GL
  if (api == Api::Gl) glMessagesAfter();
#endif
#if SAO_HARNESS_VULKAN
  // The engine-side example runs on the Vulkan test context: its messages are that context's.
  if (api == Api::Vulkan || api == Api::Engine) vkMessagesAfter();
#endif
#if SAO_HARNESS_GLES
  if (api == Api::Gles) glesMessagesAfter();
#endif
}

void ApiTest::SetUp() { checkMessagesBefore(api()); }
void ApiTest::TearDown() { checkMessagesAfter(api()); }

std::string apiName(const ::testing::TestParamInfo<Api>& info) { return toString(info.param); }

test::Scene sceneByName(const std::string& name) {
  if (name == "plane") return test::planeScene(3.0);
  if (name == "crease") return test::creaseScene(2.0);
  if (name == "sphere") return test::sphereOnPlaneScene();
  if (name == "stairs") return test::stairsScene();
  return test::rodsScene();
}

Agreement compare(Api api, const FloatImage& actual, const FloatImage& expected, std::uint32_t channel, double within,
                  double never, const std::string& name, std::string* note) {
  return test::compare(actual, expected, channel, within, never, std::string(SAO_EXEC_TEST_FAILURE_DIR) + "/" + toString(api),
                       name, note);
}

Status runCpu(const Frame& frame, cpu::Result& out, const FloatImage* history) {
  cpu::Inputs in;
  in.depth = frame.depth;
  in.depth2 = frame.depth2;
  in.normals = frame.normals;
  in.region = frame.region;
  in.outputFormat = frame.output.format;
  in.outputChannels = frame.output.channels;
  in.outputBlend = frame.output.blend;
  in.frameIndex = frame.frameIndex;
  in.output = frame.output.callerOwned ? frame.output.initial : nullptr;
  in.history = history;
  in.previousCamera = history ? frame.previousCamera : nullptr;
  in.motion = frame.motion;
  return cpu::run(frame.settings, frame.camera, in, cpu::Options{cpu::Precision::Float, 2}, out);
}

CpuAgreement expectAgreesWithCpu(Executor& executor, const cpu::Result& ref, const std::string& name) {
  const Api api = executor.api();
  EXPECT_EQ(executor.plan().cszLevels, ref.plan.cszLevels) << name;
  EXPECT_EQ(executor.plan().passes.size(), ref.plan.passes.size()) << name;
  EXPECT_EQ(std::memcmp(&executor.params(), &ref.params, sizeof ref.params), 0) << name << ": parameter blocks differ";
  const FloatImage ao = executor.output();
  CpuAgreement a;
  std::string noteFinal, noteRaw;
  a.final = compare(api, ao, ref.ao, 0, kWithin, kNever, name + "_final", &noteFinal);
  EXPECT_TRUE(acceptable(a.final)) << name << " final AO: max |diff| " << a.final.maxAbs * 255 << "/255, "
                                   << a.final.fractionWithin * 100 << "% within 2/255, " << a.final.beyond
                                   << " beyond 4/255, " << a.final.nonFinite << " non-finite; " << noteFinal;
  if (!ref.aoRaw.data.empty()) {
    const FloatImage raw = executor.image(gen::ResourceId::ao_raw);
    a.raw = compare(api, raw, ref.aoRaw, 0, kWithin, kNever, name + "_raw", &noteRaw);
    EXPECT_TRUE(acceptable(a.raw)) << name << " raw AO: max |diff| " << a.raw.maxAbs * 255 << "/255, "
                                   << a.raw.fractionWithin * 100 << "% within 2/255, " << a.raw.beyond
                                   << " beyond 4/255, " << a.raw.nonFinite << " non-finite; " << noteRaw;
    // The key (camera-space z) of the raw image is computed identically.
    std::size_t keyMismatch = 0;
    if (raw.extent == ref.aoRaw.extent && raw.channels == 2)
      for (std::size_t i = 1; i < raw.data.size(); i += 2)
        keyMismatch += std::fabs(raw.data[i] - ref.aoRaw.data[i]) > 1e-5f * std::fabs(ref.aoRaw.data[i]);
    EXPECT_EQ(keyMismatch, 0u) << name << ": raw keys (camera-space z) differ";
  }
  std::printf("AGREEMENT %-7s %-34s final max %.4f/255 p99.9 %.4f/255 within2 %.4f | raw max %.4f/255 p99.9 %.4f/255\n",
              toString(api), name.c_str(), a.final.maxAbs * 255, a.final.p999 * 255, a.final.fractionWithin,
              a.raw.maxAbs * 255, a.raw.p999 * 255);
  return a;
}

}  // namespace sao::exectest

namespace sao::exectest {

FloatImage withChannels(const FloatImage& image, std::uint32_t channels) {
  if (image.channels == channels) return image;
  FloatImage out(image.extent, channels);
  const std::size_t n = std::size_t(image.extent.width) * image.extent.height;
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t c = 0; c < std::min(channels, image.channels); ++c)
      out.data[i * channels + c] = image.data[i * image.channels + c];
  return out;
}

std::uint32_t channelsOf(Texels texels) { return texels == Texels::RG16F || texels == Texels::RG32F ? 2 : 4; }

std::uint32_t channelsOf(gen::Format format) { return gen::formatInfo(format).channels; }

Status checkLayers(const Frame& f) {
  for (const DepthImage* d : f.depthLayers)
    if (d == nullptr || d->samples > 1 || d->format != DepthFormat::D32F || f.format != Depth::D32F ||
        d->extent != f.depthLayers[0]->extent)
      return Status::error(StatusCode::InvalidInput, "harness: stereo depth layers are single-sample D32F of one extent");
  if (f.depth2 || f.normals || f.motion || !f.output.callerOwned || f.output.initial)
    return Status::error(StatusCode::InvalidInput, "harness: a stereo frame takes depth layers and the caller's output only");
  return Status::success();
}

}  // namespace sao::exectest
