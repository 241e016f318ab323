#include "vk_support.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <malloc.h>
#include <unistd.h>

namespace sao::vktest {

vk::headless::Context& context() {
  static std::unique_ptr<vk::headless::Context> ctx = [] {
    vk::headless::Options o;
    // SAO_VK_TEST_VALIDATION=0 turns the layer off (diagnostics only: e.g. to tell the layer's own
    // memory from the library's in the lifetime test).
    const char* val = std::getenv("SAO_VK_TEST_VALIDATION");
    o.validation = !(val && std::string(val) == "0");
    o.synchronizationValidation = o.validation;
    const char* dev = std::getenv("SAO_VK_TEST_DEVICE");
    if (dev && std::string(dev) == "cpu") o.device = vk::headless::DevicePreference::Cpu;
    std::unique_ptr<vk::headless::Context> c;
    const Status st = vk::headless::Context::create(o, c);
    if (!st) {
      std::fprintf(stderr, "no headless Vulkan device: %s\n", st.message.c_str());
      std::abort();
    }
    std::printf("Vulkan device: %s, %s\n", c->description().c_str(),
                o.validation ? "validation + synchronization validation" : "NO validation layer");
    std::string status = c->layerStatus();
    std::replace(status.begin(), status.end(), '\n', ' ');
    if (!status.empty()) std::printf("validation layer: %s\n", status.c_str());
    return c;
  }();
  return *ctx;
}

void expectNoMessages(const char* where) {
  const auto messages = context().takeMessages();
  EXPECT_TRUE(messages.empty()) << messages.size() << " validation message(s) " << where << ":\n"
                                << vk::headless::toString(messages);
}

void VkTest::SetUp() {
  context();
  expectNoMessages("before the test (context creation or an earlier test)");
}

void VkTest::TearDown() { expectNoMessages("during the test"); }

const char* toString(VkDepth f) {
  switch (f) {
    case VkDepth::D16: return "D16";
    case VkDepth::X8D24: return "X8D24";
    case VkDepth::D24S8: return "D24S8";
    case VkDepth::D32F: return "D32F";
    case VkDepth::D32FS8: return "D32FS8";
    case VkDepth::R32F: return "R32F";
  }
  return "?";
}

VkFormat vkFormat(VkDepth f) {
  switch (f) {
    case VkDepth::D16: return VK_FORMAT_D16_UNORM;
    case VkDepth::X8D24: return VK_FORMAT_X8_D24_UNORM_PACK32;
    case VkDepth::D24S8: return VK_FORMAT_D24_UNORM_S8_UINT;
    case VkDepth::D32F: return VK_FORMAT_D32_SFLOAT;
    case VkDepth::D32FS8: return VK_FORMAT_D32_SFLOAT_S8_UINT;
    case VkDepth::R32F: return VK_FORMAT_R32_SFLOAT;
  }
  return VK_FORMAT_UNDEFINED;
}

DepthFormat cpuFormat(VkDepth f) {
  switch (f) {
    case VkDepth::D16: return DepthFormat::D16;
    case VkDepth::X8D24:
    case VkDepth::D24S8: return DepthFormat::D24;
    case VkDepth::D32F:
    case VkDepth::D32FS8: return DepthFormat::D32F;
    case VkDepth::R32F: return DepthFormat::LinearZ;
  }
  return DepthFormat::D32F;
}

Status runEffect(const Settings& settings, const Camera& camera, const DepthImage& depth, VkDepth format,
                 RunResult& out, const RunOptions& options) {
  auto& ctx = context();
  out = RunResult{};
  vk::headless::Image depthImage, depth2Image, normalsImage;
  struct Cleanup {
    vk::headless::Image* images[3];
    ~Cleanup() { for (auto* i : images) context().destroy(*i); }
  } cleanup{{&depthImage, &depth2Image, &normalsImage}};

  // The device-level Config (defaults); the frame's settings, camera and inputs (their formats and
  // the depth's samples) go to the first record(), which plans.
  const vk::Config config;
  vk::Inputs in;
  if (options.depthImage) {
    in.depth = *options.depthImage;
    if (in.depth.format == VK_FORMAT_UNDEFINED) in.depth.format = vkFormat(format);
  } else {
    if (Status st = ctx.uploadDepth(depth, vkFormat(format), options.depthLayout, depthImage); !st) return st;
    in.depth = {depthImage.view, options.depthLayout, depth.extent, vkFormat(format)};
  }
  if (options.depthSamples != VK_SAMPLE_COUNT_1_BIT) in.depth.samples = options.depthSamples;
  in.region = options.region;
  if (options.depth2) {
    if (Status st = ctx.uploadDepth(*options.depth2, vkFormat(format), options.depthLayout, depth2Image); !st) return st;
    in.depth2 = {depth2Image.view, options.depthLayout, options.depth2->extent, vkFormat(format)};
  }
  if (options.normals) {
    const VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    if (Status st = ctx.uploadColor(*options.normals, options.normalsFormat, layout, normalsImage); !st) return st;
    in.normals = {normalsImage.view, layout, options.normals->extent, options.normalsFormat};
  }
  std::unique_ptr<vk::Effect> effect;
  if (Status st = vk::Effect::create(ctx.deviceContext(), config, effect); !st) return st;
  if (Status st = submitRecord([&](VkCommandBuffer cmd) { return effect->record(cmd, camera, settings, in); }); !st)
    return st;
  out.plan = effect->plan();
  out.params = effect->params();
  const vk::OutputImage o = effect->output();
  if (Status st = ctx.readback(o.image, o.format, o.extent, 0, o.layout, config.outputDstStages, config.outputDstAccess,
                               out.ao);
      !st)
    return st;
  if (!options.readIntermediates) return Status::success();
  // Level `m` of one of the effect's images, last written by a compute shader.
  const auto read = [&](gen::ResourceId id, std::uint32_t m, FloatImage& to) {
    const auto i = effect->ownedImage(id);
    return ctx.readback(i.image, i.format, i.extent, m, i.layout, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                        VK_ACCESS_SHADER_WRITE_BIT, to);
  };
  out.aoRawFormat = effect->ownedImage(gen::ResourceId::ao_raw).format;
  if (Status st = read(gen::ResourceId::ao_raw, 0, out.aoRaw); !st) return st;
  if (Status st = read(gen::ResourceId::csz, 0, out.csz0); !st) return st;
  for (const gen::ResourceId id : {gen::ResourceId::csz, gen::ResourceId::csz2, gen::ResourceId::csz_share}) {
    if (!options.readChain || out.plan.image(id) == nullptr) continue;
    auto& levels = id == gen::ResourceId::csz ? out.csz : id == gen::ResourceId::csz2 ? out.csz2 : out.cszShare;
    levels.resize(out.plan.cszLevels);
    for (std::uint32_t m = 0; m < out.plan.cszLevels; ++m)
      if (Status st = read(id, m, levels[m]); !st) return st;
  }
  if (out.plan.image(gen::ResourceId::ao_low) != nullptr) return read(gen::ResourceId::ao_low, 0, out.aoLow);
  return Status::success();
}

std::unique_ptr<vk::Effect> makeEffect(const vk::Config& config) {
  std::unique_ptr<vk::Effect> e;
  const Status st = vk::Effect::create(context().deviceContext(), config, e);
  EXPECT_TRUE(st.ok()) << st.message;
  return e;
}

Status submitRecord(const std::function<Status(VkCommandBuffer)>& record) {
  Status recorded;
  const Status submitted = context().submit([&](VkCommandBuffer cmd) { recorded = record(cmd); });
  EXPECT_TRUE(submitted.ok()) << submitted.message;
  return recorded;
}

FloatImage readOutput(const vk::Effect& e, const vk::OutputImage* userOutput) {
  const vk::OutputImage o = userOutput ? *userOutput : e.output();
  FloatImage ao;
  const Status st = context().readback(o.image, o.format, o.extent, 0, userOutput ? e.config().outputLayout : o.layout,
                                       e.config().outputDstStages, e.config().outputDstAccess, ao);
  EXPECT_TRUE(st.ok()) << st.message;
  return ao;
}

FloatImage recordAndRead(vk::Effect& e, const Camera& camera, const Settings& settings, const vk::Inputs& in,
                         const vk::OutputImage* userOutput) {
  const Status recorded = submitRecord([&](VkCommandBuffer cmd) { return e.record(cmd, camera, settings, in, userOutput); });
  EXPECT_TRUE(recorded.ok()) << recorded.message;
  return readOutput(e, userOutput);
}

void expectStatus(const Status& st, StatusCode code, const std::string& needle, const std::string& what) {
  EXPECT_EQ(st.code, code) << what << ": " << toString(st.code) << ": " << st.message;
  EXPECT_FALSE(st.message.empty()) << what;
  EXPECT_NE(st.message.find(needle), std::string::npos) << what << ": expected \"" << needle << "\" in: " << st.message;
}

std::string failureDir() { return SAO_VK_TEST_FAILURE_DIR; }

std::uint64_t residentBytes() {
  malloc_trim(0);  // return freed heap pages first: count live memory, not the allocator's free lists
  std::ifstream f("/proc/self/statm");
  std::uint64_t size = 0, resident = 0;
  f >> size >> resident;
  return resident * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

}  // namespace sao::vktest
