// sao-vk-frame-loop-probe: host memory of a long Vulkan frame loop, for bisecting growth (issue 19).
//
// Records the effect once into 2 command buffers (or afresh every frame with --rerecord; the
// first record, which plans, is made before the loop either way) and resubmits them for --frames
// frames with 2 in flight, printing mallinfo2().uordblks and RSS every 100 frames and the growth
// per frame after a 100-frame warm-up (and, with validation, the layer's messages at the end).
// --drop=CMD[,CMD...] interposes vkGetDeviceProcAddr and replaces those commands with no-ops, so
// each command of the stream can be switched off in turn: vkCmdWriteTimestamp, vkCmdResetQueryPool,
// vkCmdPipelineBarrier, vkCmdBindDescriptorSets, vkCmdDispatch, or dispatch:N (only the N-th
// dispatch of each record; the dispatch list is printed). Results with commands dropped are
// meaningless as pixels; this is a memory probe, not a test.
//   sao-vk-frame-loop-probe [--frames N] [--size WxH] [--timestamps] [--labels] [--validation]
//                           [--rerecord] [--set name=value] [--drop=...] [--replace-spv ORIG=NEW]
//                           [--no-optimization]
#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "analytic_scenes.h"
#include "sao/schedule.h"
#include "sao/settings.h"
#include "sao/vulkan/effect.h"
#include "sao/vulkan/headless.h"
#include "test_cameras.h"

namespace {

std::vector<std::string> gDropped;
int gDispatchToDrop = -1;
int gDispatchIndex = 0;
PFN_vkCmdDispatch gRealDispatch = nullptr;
// --replace-spv ORIG=NEW: a module created from exactly ORIG's words is created from NEW instead
// (for bisecting one shader: compile an edited copy of build/effect/sao_effect/<pass>.glsl).
std::string gOriginalSpv, gReplacementSpv;
PFN_vkCreateShaderModule gRealCreateShaderModule = nullptr;

std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

VKAPI_ATTR VkResult VKAPI_CALL replacingCreateShaderModule(VkDevice device, const VkShaderModuleCreateInfo* info,
                                                           const VkAllocationCallbacks* allocator,
                                                           VkShaderModule* module) {
  if (!gOriginalSpv.empty() && info->codeSize == gOriginalSpv.size() &&
      std::memcmp(info->pCode, gOriginalSpv.data(), info->codeSize) == 0) {
    VkShaderModuleCreateInfo other = *info;
    other.codeSize = gReplacementSpv.size();
    other.pCode = reinterpret_cast<const std::uint32_t*>(gReplacementSpv.data());
    std::printf("replaced a shader module (%zu bytes) by %zu bytes\n", gOriginalSpv.size(), gReplacementSpv.size());
    return gRealCreateShaderModule(device, &other, allocator, module);
  }
  return gRealCreateShaderModule(device, info, allocator, module);
}

bool dropped(const char* name) {
  for (const std::string& d : gDropped)
    if (d == name) return true;
  return false;
}

VKAPI_ATTR void VKAPI_CALL noWriteTimestamp(VkCommandBuffer, VkPipelineStageFlagBits, VkQueryPool, uint32_t) {}
VKAPI_ATTR void VKAPI_CALL noResetQueryPool(VkCommandBuffer, VkQueryPool, uint32_t, uint32_t) {}
VKAPI_ATTR void VKAPI_CALL noPipelineBarrier(VkCommandBuffer, VkPipelineStageFlags, VkPipelineStageFlags,
                                             VkDependencyFlags, uint32_t, const VkMemoryBarrier*, uint32_t,
                                             const VkBufferMemoryBarrier*, uint32_t, const VkImageMemoryBarrier*) {}
VKAPI_ATTR void VKAPI_CALL noBindDescriptorSets(VkCommandBuffer, VkPipelineBindPoint, VkPipelineLayout, uint32_t,
                                                uint32_t, const VkDescriptorSet*, uint32_t, const uint32_t*) {}
VKAPI_ATTR void VKAPI_CALL someDispatch(VkCommandBuffer cmd, uint32_t x, uint32_t y, uint32_t z) {
  const int k = gDispatchIndex++;
  if (dropped("vkCmdDispatch") || k == gDispatchToDrop) return;
  gRealDispatch(cmd, x, y, z);
}

bool gNoOptimization = false;  // --no-optimization: VK_PIPELINE_CREATE_DISABLE_OPTIMIZATION_BIT on every pipeline
PFN_vkCreateComputePipelines gRealCreateComputePipelines = nullptr;
VKAPI_ATTR VkResult VKAPI_CALL flaggedCreateComputePipelines(VkDevice device, VkPipelineCache cache, uint32_t n,
                                                             const VkComputePipelineCreateInfo* infos,
                                                             const VkAllocationCallbacks* allocator,
                                                             VkPipeline* pipelines) {
  std::vector<VkComputePipelineCreateInfo> copy(infos, infos + n);
  for (VkComputePipelineCreateInfo& i : copy)
    if (gNoOptimization) i.flags |= VK_PIPELINE_CREATE_DISABLE_OPTIMIZATION_BIT;
  return gRealCreateComputePipelines(device, cache, n, copy.data(), allocator, pipelines);
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL probeGetDeviceProcAddr(VkDevice device, const char* name) {
  auto as = [](auto f) { return reinterpret_cast<PFN_vkVoidFunction>(f); };
  if (std::strcmp(name, "vkCmdDispatch") == 0) {
    gRealDispatch = reinterpret_cast<PFN_vkCmdDispatch>(vkGetDeviceProcAddr(device, name));
    return as(&someDispatch);
  }
  if (std::strcmp(name, "vkCreateComputePipelines") == 0) {
    gRealCreateComputePipelines = reinterpret_cast<PFN_vkCreateComputePipelines>(vkGetDeviceProcAddr(device, name));
    return as(&flaggedCreateComputePipelines);
  }
  if (std::strcmp(name, "vkCreateShaderModule") == 0) {
    gRealCreateShaderModule = reinterpret_cast<PFN_vkCreateShaderModule>(vkGetDeviceProcAddr(device, name));
    return as(&replacingCreateShaderModule);
  }
  if (dropped(name)) {
    if (!std::strcmp(name, "vkCmdWriteTimestamp")) return as(&noWriteTimestamp);
    if (!std::strcmp(name, "vkCmdResetQueryPool")) return as(&noResetQueryPool);
    if (!std::strcmp(name, "vkCmdPipelineBarrier")) return as(&noPipelineBarrier);
    if (!std::strcmp(name, "vkCmdBindDescriptorSets")) return as(&noBindDescriptorSets);
  }
  return vkGetDeviceProcAddr(device, name);
}

std::uint64_t residentBytes() {
  long pages = 0, resident = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return static_cast<std::uint64_t>(resident) * 4096u;
}

int fail(const std::string& what) {
  std::fprintf(stderr, "sao-vk-frame-loop-probe: %s\n", what.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 1000, width = 64, height = 64;
  bool timestamps = false, labels = false, validation = false, rerecord = false;
  sao::Settings settings;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (a == "--size" && i + 1 < argc && std::sscanf(argv[++i], "%dx%d", &width, &height) == 2) {}
    else if (a == "--timestamps") timestamps = true;
    else if (a == "--labels") labels = true;
    else if (a == "--validation") validation = true;
    else if (a == "--rerecord") rerecord = true;
    else if (a == "--no-optimization") gNoOptimization = true;
    else if (a == "--replace-spv" && i + 1 < argc) {
      const std::string v = argv[++i];
      const std::size_t eq = v.find('=');
      if (eq == std::string::npos) return fail("--replace-spv ORIG.spv=NEW.spv");
      gOriginalSpv = readFile(v.substr(0, eq));
      gReplacementSpv = readFile(v.substr(eq + 1));
      if (gOriginalSpv.empty() || gReplacementSpv.size() % 4) return fail("cannot read " + v);
    } else if (a == "--set" && i + 1 < argc) {
      if (sao::Status st = sao::setFromAssignment(settings, argv[++i]); !st) return fail(st.message);
    }
    else if (a.rfind("--drop=", 0) == 0) {
      std::string list = a.substr(7);
      for (std::size_t p = 0; p <= list.size();) {
        const std::size_t q = std::min(list.find(',', p), list.size());
        const std::string item = list.substr(p, q - p);
        if (item.rfind("dispatch:", 0) == 0) gDispatchToDrop = std::atoi(item.c_str() + 9);
        else if (item == "vkCmdWriteTimestamp" || item == "vkCmdResetQueryPool" || item == "vkCmdPipelineBarrier" ||
                 item == "vkCmdBindDescriptorSets" || item == "vkCmdDispatch")
          gDropped.push_back(item);
        else if (!item.empty())
          return fail("--drop: '" + item + "' is not a command this probe can drop");
        p = q + 1;
      }
    } else return fail("unknown argument '" + a + "' (see the comment at the top of frame_loop_probe.cpp)");
  }
  if (frames < 200 || width < 8 || height < 8) return fail("--frames >= 200 and --size at least 8x8");

  sao::vk::headless::Options o;
  o.validation = validation || labels;
  std::unique_ptr<sao::vk::headless::Context> ctx;
  if (sao::Status st = sao::vk::headless::Context::create(o, ctx); !st) return fail(st.message);
  sao::vk::DeviceContext dc = ctx->deviceContext();
  dc.getDeviceProcAddr = &probeGetDeviceProcAddr;
  dc.debugUtilsEnabled = labels;

  const sao::Camera camera = sao::test::vulkanCamera(width, height, 4);
  const sao::DepthImage depth =
      sao::test::renderDepth(sao::test::sphereOnPlaneScene(), camera, sao::DepthFormat::D32F);
  sao::vk::headless::Image image;
  if (sao::Status st = ctx->uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image);
      !st)
    return fail(st.message);
  sao::vk::Config config;
  config.framesInFlight = 2;
  config.timestamps = timestamps;
  std::unique_ptr<sao::vk::Effect> effect;
  if (sao::Status st = sao::vk::Effect::create(dc, config, effect); !st) return fail(st.message);
  sao::vk::Inputs in;
  in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};

  VkDevice device = ctx->device();
  VkCommandBuffer cmds[2]{};
  VkFence fences[2]{};
  if (!ctx->allocateCommandBuffers(cmds, 2)) return fail("vkAllocateCommandBuffers");
  for (VkFence& f : fences) {
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
    if (vkCreateFence(device, &fi, nullptr, &f) != VK_SUCCESS) return fail("vkCreateFence");
  }
  auto recordInto = [&](VkCommandBuffer cmd) {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd, &bi);
    gDispatchIndex = 0;
    const sao::Status st = effect->record(cmd, camera, settings, in);
    vkEndCommandBuffer(cmd);
    return st;
  };
  // The first record plans (the dispatch list below is the plan's). With --rerecord only the first
  // command buffer is recorded here, to plan; the loop records it again before submitting it.
  for (VkCommandBuffer c : cmds) {
    if (sao::Status st = recordInto(c); !st) return fail(st.message);
    if (rerecord) break;
  }

  std::printf("device: %s; %dx%d, %d frames, timestamps %s, labels %s, validation %s, %s, dropped:", 
              ctx->description().c_str(), width, height, frames, timestamps ? "on" : "off", labels ? "on" : "off",
              o.validation ? "on" : "off", rerecord ? "re-recorded every frame" : "recorded once");
  for (const std::string& d : gDropped) std::printf(" %s", d.c_str());
  if (gDispatchToDrop >= 0) std::printf(" dispatch #%d", gDispatchToDrop);
  std::printf("\ndispatches:");
  const sao::Schedule schedule = sao::makeSchedule(effect->plan());
  for (std::size_t k = 0; k < schedule.dispatches.size(); ++k) {
    const sao::ScheduledDispatch& d = schedule.dispatches[k];
    std::printf(" #%zu %.*s L%u %ux%u;", k, static_cast<int>(sao::gen::pass(d.pass).name.size()),
                sao::gen::pass(d.pass).name.data(), d.level, d.groupsX, d.groupsY);
  }
  std::printf("\n%8s %14s %14s\n", "frame", "uordblks", "rss");
  std::uint64_t warmHeap = 0, warmRss = 0;
  const int warmUp = 100;
  for (int f = 0; f < frames; ++f) {
    const int k = f % 2;
    if (vkWaitForFences(device, 1, &fences[k], VK_TRUE, UINT64_MAX) != VK_SUCCESS) return fail("vkWaitForFences");
    vkResetFences(device, 1, &fences[k]);
    if (rerecord)
      if (sao::Status st = recordInto(cmds[k]); !st) return fail(st.message);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmds[k];
    if (vkQueueSubmit(ctx->queue(), 1, &si, fences[k]) != VK_SUCCESS) return fail("vkQueueSubmit");
    if ((f + 1) % 100 == 0) {
      const std::uint64_t heap = mallinfo2().uordblks, rss = residentBytes();
      std::printf("%8d %14llu %14llu\n", f + 1, static_cast<unsigned long long>(heap),
                  static_cast<unsigned long long>(rss));
      std::fflush(stdout);
      if (f + 1 == warmUp) warmHeap = heap, warmRss = rss;
    }
  }
  vkDeviceWaitIdle(device);
  const double n = frames - warmUp;
  const double heapPerFrame = (double(mallinfo2().uordblks) - double(warmHeap)) / n;
  const double rssPerFrame = (double(residentBytes()) - double(warmRss)) / n;
  std::printf("growth after the warm-up: %.1f heap bytes/frame, %.1f RSS bytes/frame\n", heapPerFrame, rssPerFrame);
  for (VkFence f : fences) vkDestroyFence(device, f, nullptr);
  vkFreeCommandBuffers(device, ctx->commandPool(), 2, cmds);
  effect.reset();
  ctx->destroy(image);
  // Reported, not failed on: a dropped barrier (--drop) makes hazards on purpose.
  if (o.validation) {
    const std::vector<sao::vk::headless::Message> messages = ctx->takeMessages();
    std::printf("validation messages: %zu\n%s", messages.size(), sao::vk::headless::toString(messages).c_str());
  }
  return 0;
}
