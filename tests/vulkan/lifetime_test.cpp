// 200 create -> record -> submit -> destroy cycles, 200 resizes and 1,000 create -> resize -> destroy
// cycles (validation and synchronization validation on, as everywhere in this suite). A resize is
// a record() with another camera: it plans again within the call and keeps what the old plan alone
// used until Config::framesInFlight records after it have been made. Checked:
//  * device memory: the library allocator's counters come back exactly (per effect and for the
//    process) and each size always holds the same bytes;
//  * host memory of every Vulkan object the effect creates: counted through the
//    VkAllocationCallbacks passed in DeviceContext::allocator, back to the baseline after every
//    destroy and the same for each size;
//  * the process RSS after a warm-up. Mesa's lavapipe (22.3) itself retains host memory for every
//    dispatch of the ao_sample shader (about 20 KB per work group, released only with the
//    VkDevice; reproduced below without sao::vk), so the RSS growth is compared with that of
//    plain-Vulkan dispatches of the same shader, the same number of times at the same sizes,
//    measured in this process: the library may add at most kAllowedGrowth on top.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <mutex>
#include <string>

#include "analytic_scenes.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;

constexpr int kCycles = 200;
constexpr int kWarmup = 40;  // caches of the driver, the layer and the allocator settle first
// RSS bytes beyond the driver's own over the 160 measured iterations (about 26 KB per iteration: far
// below any image or pipeline; device memory and the objects' host memory are checked exactly).
constexpr std::uint64_t kAllowedGrowth = 4ull << 20;

// Process RSS at the end of the warm-up, half way through the measured cycles and at the end. A
// per-cycle leak grows RSS in both halves; a one-time step (the allocator's or the driver's pools
// growing once: the same binary measured -0.5, +3.3 and +5.1 MiB end minus warm-up in three runs,
// which failed CI by chance) lands in one half only. growth() is twice the smaller half: a step
// anywhere does not read as a leak, and a steady leak still reads as its whole amount.
class RssHalves {
 public:
  RssHalves(int warmup, int cycles) : warmLast_(warmup - 1), midLast_(warmup - 1 + (cycles - warmup) / 2) {}
  void afterCycle(int i) {
    if (i == warmLast_) warm_ = residentBytes();
    if (i == midLast_) mid_ = residentBytes();
  }
  void atEnd() { end_ = residentBytes(); }
  double growth() const {
    return 2.0 * std::min(double(mid_) - double(warm_), double(end_) - double(mid_));
  }
  double endMinusWarm() const { return double(end_) - double(warm_); }

 private:
  int warmLast_, midLast_;
  std::uint64_t warm_ = 0, mid_ = 0, end_ = 0;
};

// ---- VkAllocationCallbacks that count live host bytes and allocations.
struct HostCounter {
  std::mutex m;
  std::map<void*, std::size_t> live;
  std::uint64_t bytes = 0, total = 0;
  std::pair<std::uint64_t, std::size_t> snapshot() {
    std::lock_guard l(m);
    return {bytes, live.size()};
  }
};
HostCounter gHost;

void* VKAPI_CALL countedAlloc(void*, std::size_t size, std::size_t align, VkSystemAllocationScope) {
  if (size == 0) return nullptr;
  // aligned_alloc wants the size a multiple of the alignment actually used (ASan checks it).
  const std::size_t a = std::max<std::size_t>(align, 16);
  void* p = std::aligned_alloc(a, (size + a - 1) / a * a);
  if (!p) return nullptr;
  std::lock_guard l(gHost.m);
  gHost.live[p] = size;
  gHost.bytes += size;
  ++gHost.total;
  return p;
}
void VKAPI_CALL countedFree(void*, void* p) {
  if (!p) return;
  {
    std::lock_guard l(gHost.m);
    auto it = gHost.live.find(p);
    if (it != gHost.live.end()) {
      gHost.bytes -= it->second;
      gHost.live.erase(it);
    }
  }
  std::free(p);
}
void* VKAPI_CALL countedRealloc(void* user, void* old, std::size_t size, std::size_t align, VkSystemAllocationScope s) {
  if (!old) return countedAlloc(user, size, align, s);
  if (size == 0) {
    countedFree(user, old);
    return nullptr;
  }
  std::size_t oldSize = 0;
  {
    std::lock_guard l(gHost.m);
    oldSize = gHost.live[old];
  }
  void* p = countedAlloc(user, size, align, s);
  if (p) {
    std::memcpy(p, old, std::min(oldSize, size));
    countedFree(user, old);
  }
  return p;
}
const VkAllocationCallbacks kCounted{nullptr, &countedAlloc, &countedRealloc, &countedFree, nullptr, nullptr};

vk::DeviceContext countedContext() {
  vk::DeviceContext c = context().deviceContext();
  c.allocator = &kCounted;
  return c;
}

// ---- The effect's ao_sample shader dispatched with plain Vulkan (no sao::vk): the driver's own
// host-memory behaviour for the same work.
class RawAoSample {
 public:
  RawAoSample(const Settings& settings, const Camera& camera) {
    Plan plan;
    EXPECT_TRUE(sao::plan(settings, camera, {}, plan).ok());
    EXPECT_TRUE(computeConstants(settings, camera, DepthEncoding::Hardware, params_).ok());
    for (const auto& p : plan.passes)
      if (p.pass == gen::PassId::ao_sample) variant_ = p.variant;
    input_ = plan.inputExtent;
    ao_ = plan.aoExtent;
    levels_ = plan.cszLevels;
    const VkDevice d = context().device();
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.maxLod = VK_LOD_CLAMP_NONE;
    vkCreateSampler(d, &si, nullptr, &sampler_);
    std::vector<VkDescriptorSetLayoutBinding> b{{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
    for (const auto& x : variant_->bindings) {
      EXPECT_TRUE(x.resource == gen::ResourceId::csz || x.resource == gen::ResourceId::ao_raw);
      b.push_back({x.binding, x.write ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                   VK_SHADER_STAGE_COMPUTE_BIT, x.write ? nullptr : &sampler_});
    }
    VkDescriptorSetLayoutCreateInfo dl{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr, 0,
                                       std::uint32_t(b.size()), b.data()};
    vkCreateDescriptorSetLayout(d, &dl, nullptr, &setLayout_);
    // The loop counts as ao_sample's SPIR-V reads them: the generated push constants.
    const VkPushConstantRange pushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, variant_->pushConstantBytes};
    VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 1, &setLayout_, 1, &pushRange};
    vkCreatePipelineLayout(d, &pl, nullptr, &layout_);
    makePipeline();
    EXPECT_TRUE(context().createStorageImage(VK_FORMAT_R32G32_SFLOAT, ao_, aoRaw_).ok());
    csz_ = makeImage(VK_FORMAT_R32_SFLOAT, input_, levels_);
    EXPECT_TRUE(context().createBuffer(sizeof(ParamBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, ubo_).ok());
    std::memcpy(ubo_.mapped, &params_, sizeof(ParamBlock));
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                          {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, 1, 3, sizes};
    vkCreateDescriptorPool(d, &pi, nullptr, &pool_);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, pool_, 1, &setLayout_};
    vkAllocateDescriptorSets(d, &ai, &set_);
    const VkDescriptorBufferInfo ub{ubo_.buffer, 0, sizeof(ParamBlock)};
    std::vector<VkDescriptorImageInfo> infos;
    infos.reserve(variant_->bindings.size());
    std::vector<VkWriteDescriptorSet> w{{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set_, 0, 0, 1,
                                         VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, nullptr, &ub, nullptr}};
    for (const auto& x : variant_->bindings) {
      infos.push_back({VK_NULL_HANDLE, x.write ? aoRaw_.view : cszView_, VK_IMAGE_LAYOUT_GENERAL});
      w.push_back({VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set_, x.binding, 0, 1,
                   x.write ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                   &infos.back(), nullptr, nullptr});
    }
    vkUpdateDescriptorSets(d, std::uint32_t(w.size()), w.data(), 0, nullptr);
    const Status st = context().submit([&](VkCommandBuffer cmd) {
      const auto bar = vk::headless::imageBarrier(csz_, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                                  VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_SHADER_READ_BIT, 0, levels_);
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                           nullptr, 1, &bar);
    });
    EXPECT_TRUE(st.ok()) << st.message;
  }
  ~RawAoSample() {
    const VkDevice d = context().device();
    vkDestroyDescriptorPool(d, pool_, nullptr);
    context().destroy(ubo_);
    vkDestroyImageView(d, cszView_, nullptr);
    vkDestroyImage(d, csz_, nullptr);
    vkFreeMemory(d, cszMemory_, nullptr);
    context().destroy(aoRaw_);
    vkDestroyPipeline(d, pipeline_, nullptr);
    vkDestroyPipelineLayout(d, layout_, nullptr);
    vkDestroyDescriptorSetLayout(d, setLayout_, nullptr);
    vkDestroySampler(d, sampler_, nullptr);
  }
  void recreatePipeline() {
    vkDestroyPipeline(context().device(), pipeline_, nullptr);
    makePipeline();
  }
  void dispatch() {
    const Status st = context().submit([&](VkCommandBuffer cmd) {
      const auto bar = vk::headless::imageBarrier(aoRaw_.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                                  VK_IMAGE_LAYOUT_GENERAL, VK_ACCESS_SHADER_WRITE_BIT,
                                                  VK_ACCESS_SHADER_WRITE_BIT);
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 1, &bar);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
      const gen::PushConstants constants = gen::pushConstantsOf(params_);
      vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, variant_->pushConstantBytes, &constants);
      vkCmdDispatch(cmd, (ao_.width + 7) / 8, (ao_.height + 7) / 8, 1);
    });
    EXPECT_TRUE(st.ok()) << st.message;
  }

 private:
  void makePipeline() {
    const auto code = gen::spirvModule(variant_->spirvBlob);
    VkShaderModuleCreateInfo sm{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, code.size_bytes(), code.data()};
    VkShaderModule module = VK_NULL_HANDLE;
    vkCreateShaderModule(context().device(), &sm, nullptr, &module);
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main", nullptr};
    ci.layout = layout_;
    vkCreateComputePipelines(context().device(), VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
    vkDestroyShaderModule(context().device(), module, nullptr);
  }
  VkImage makeImage(VkFormat format, Extent e, std::uint32_t levels) {
    const VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, nullptr, 0, VK_IMAGE_TYPE_2D, format,
                               {e.width, e.height, 1}, levels, 1, VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_TILING_OPTIMAL,
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT};
    VkImage img = VK_NULL_HANDLE;
    vkCreateImage(context().device(), &ci, nullptr, &img);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(context().device(), img, &req);
    std::uint32_t type = 0;  // the first type the image can live in
    while (!(req.memoryTypeBits & (1u << type))) ++type;
    const VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
    vkAllocateMemory(context().device(), &ai, nullptr, &cszMemory_);
    vkBindImageMemory(context().device(), img, cszMemory_, 0);
    const VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, nullptr, 0, img, VK_IMAGE_VIEW_TYPE_2D, format,
                                   {}, {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1}};
    vkCreateImageView(context().device(), &vi, nullptr, &cszView_);
    return img;
  }

  const gen::PassVariantInfo* variant_ = nullptr;
  ParamBlock params_{};
  Extent input_, ao_;
  std::uint32_t levels_ = 1;
  VkSampler sampler_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  Image aoRaw_;
  VkImage csz_ = VK_NULL_HANDLE;
  VkImageView cszView_ = VK_NULL_HANDLE;
  VkDeviceMemory cszMemory_ = VK_NULL_HANDLE;
  vk::headless::Buffer ubo_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

struct Uploaded {
  Camera camera;
  DepthImage depth;
  Image image;
};

Uploaded upload(std::uint32_t w, std::uint32_t h) {
  Uploaded u;
  u.camera = vulkanCamera(w, h, 4);
  u.depth = test::renderDepth(test::sphereOnPlaneScene(), u.camera, DepthFormat::D24);
  const Status st = context().uploadDepth(u.depth, VK_FORMAT_X8_D24_UNORM_PACK32,
                                          VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, u.image);
  EXPECT_TRUE(st.ok()) << st.message;
  return u;
}

vk::Inputs inputsOf(const Uploaded& u) {
  vk::Inputs in;
  in.depth = {u.image.view, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, u.depth.extent,
              VK_FORMAT_X8_D24_UNORM_PACK32};
  return in;
}

const Settings kSettings{};  // every record's: the defaults

// Records `u`'s frame (its camera, kSettings) into a command buffer that is submitted and waited for.
Status recordAndSubmit(vk::Effect& e, const Uploaded& u) {
  return submitRecord([&](VkCommandBuffer cmd) { return e.record(cmd, u.camera, kSettings, inputsOf(u)); });
}

double mib(double bytes) { return bytes / 1048576.0; }

// Under AddressSanitizer freed memory sits in the allocator's quarantine: RSS says nothing there
// (ci/sanitize.sh sets SAO_SANITIZED for the uninstrumented-compiler case too). The exact device-
// and host-memory counters are checked in every build.
bool sanitized() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#else
  return std::getenv("SAO_SANITIZED") != nullptr;
#endif
}

// The RSS growth of an effect's cycles, which `loop` runs, filling the halves it is given. Both halves
// grew once in a CI run (+4.2 MiB, twice the smaller half, against 0.2 - 1.0 MiB in every run before
// and after, alone or beside another lifetime test): a leak grows again in a second measurement, such
// a step does not, so above `bound` the cycles run again and the second measurement decides (the note
// says what the first read). Not under the sanitizers, where RSS is not checked.
struct RssGrowth {
  double growth = 0, endMinusWarm = 0;
  std::string note;
};
RssGrowth measureRssGrowth(int warmup, int cycles, double bound, const std::function<void(RssHalves&)>& loop) {
  RssHalves rss(warmup, cycles);
  loop(rss);
  RssGrowth g{rss.growth(), rss.endMinusWarm(), ""};
  if (sanitized() || ::testing::Test::HasFatalFailure() || g.growth <= bound) return g;
  RssHalves again(warmup, cycles);
  loop(again);
  g.note = " (a first measurement read " + std::to_string(mib(g.growth)) + " MiB; measured again)";
  g.growth = again.growth();
  g.endMinusWarm = again.endMinusWarm();
  return g;
}

// The plain-Vulkan baseline: `iteration(i)` run `cycles` times; its RSS growth (RssHalves).
double baselineGrowth(int warmup, int cycles, const std::function<void(int)>& iteration) {
  RssHalves rss(warmup, cycles);
  for (int i = 0; i < cycles; ++i) {
    iteration(i);
    rss.afterCycle(i);
  }
  rss.atEnd();
  expectNoMessages("in the plain-Vulkan baseline");
  return rss.growth();
}

// The RSS growth of `loop` (measureRssGrowth), at most kAllowedGrowth beyond the baseline's
// (not under the sanitizers).
RssGrowth expectRssGrowthWithin(double rawGrowth, int warmup, int cycles, const char* what,
                                const std::function<void(RssHalves&)>& loop) {
  const double bound = std::max(0.0, rawGrowth) + double(kAllowedGrowth);
  const RssGrowth rss = measureRssGrowth(warmup, cycles, bound, loop);
  if (!sanitized() && !::testing::Test::HasFatalFailure()) {
    EXPECT_LE(rss.growth, bound) << "host memory grows with " << what << " beyond what the driver itself retains"
                                 << rss.note;
  }
  return rss;
}

// Device memory and the host memory of the effect's Vulkan objects are back where they were.
void expectBackTo(const vk::MemoryStats& before, std::pair<std::uint64_t, std::size_t> hostBefore, int cycle) {
  const vk::MemoryStats now = vk::processMemoryStats();
  ASSERT_EQ(now.liveAllocations, before.liveAllocations) << "cycle " << cycle;
  ASSERT_EQ(now.liveBytes, before.liveBytes) << "cycle " << cycle;
  ASSERT_EQ(gHost.snapshot(), hostBefore) << "host memory of the effect's Vulkan objects, cycle " << cycle;
}

class VkLifetime : public VkTest {};

TEST_F(VkLifetime, CreateRecordSubmitDestroy200Times) {
  Uploaded u = upload(48, 27);
  vk::Config config;
  config.timestamps = true;

  // The driver alone: a new ao_sample pipeline and one dispatch per iteration.
  double rawGrowth = 0;
  {
    RawAoSample raw(kSettings, u.camera);
    rawGrowth = baselineGrowth(kWarmup, kCycles, [&](int) {
      raw.recreatePipeline();
      raw.dispatch();
    });
  }

  const vk::MemoryStats before = vk::processMemoryStats();
  const auto hostBefore = gHost.snapshot();
  std::uint64_t peakBytes = 0, peakHost = 0;
  // kCycles cycles, every exact counter checked after each; the RSS halves measured in `rss`.
  const auto cycles = [&](RssHalves& rss) {
    for (int i = 0; i < kCycles; ++i) {
      {
        std::unique_ptr<vk::Effect> effect;
        const Status st = vk::Effect::create(countedContext(), config, effect);
        ASSERT_TRUE(st.ok()) << st.message;
        const Status recorded = recordAndSubmit(*effect, u);  // the first record plans
        ASSERT_TRUE(recorded.ok()) << recorded.message;
        peakBytes = std::max(peakBytes, vk::processMemoryStats().liveBytes);
        peakHost = std::max(peakHost, gHost.snapshot().first);
      }
      expectBackTo(before, hostBefore, i);
      if (::testing::Test::HasFatalFailure()) return;
      rss.afterCycle(i);
      if (i % 50 == 49) expectNoMessages(("by cycle " + std::to_string(i)).c_str());
    }
    rss.atEnd();
  };
  const RssGrowth rss = expectRssGrowthWithin(rawGrowth, kWarmup, kCycles, "create/destroy cycles", cycles);
  if (HasFatalFailure()) return;
  const vk::MemoryStats after = vk::processMemoryStats();
  EXPECT_GE(after.totalAllocations - before.totalAllocations, std::uint64_t(kCycles));
  std::printf("%d create/record/submit/destroy cycles: device memory live %llu -> %llu bytes (peak %llu, %llu "
              "allocations made); host memory of the effect's Vulkan objects %llu -> %llu bytes (peak %llu); RSS "
              "growth over cycles %d..%d %+.3f MiB (twice the smaller half; end minus warm-up %+.3f)%s, plain-Vulkan "
              "baseline (same pipeline + dispatch per cycle) %+.3f MiB\n",
              kCycles, (unsigned long long)before.liveBytes, (unsigned long long)after.liveBytes,
              (unsigned long long)peakBytes, (unsigned long long)(after.totalAllocations - before.totalAllocations),
              (unsigned long long)hostBefore.first, (unsigned long long)gHost.snapshot().first,
              (unsigned long long)peakHost, kWarmup, kCycles, mib(rss.growth), mib(rss.endMinusWarm), rss.note.c_str(),
              mib(rawGrowth));
  context().destroy(u.image);
}

TEST_F(VkLifetime, Resize200Times) {
  // Eight sizes visited in a scrambled order: every cycle's first record() is a resize. The old
  // plan's images go once framesInFlight records follow it: each cycle records its size that many
  // times more, after which the effect holds that size's memory alone.
  const Extent sizes[] = {{32, 18}, {48, 27}, {64, 36}, {40, 30}, {80, 45}, {56, 20}, {24, 40}, {72, 50}};
  std::vector<Uploaded> frames;
  for (const auto& s : sizes) frames.push_back(upload(s.width, s.height));
  std::vector<std::size_t> order;
  std::size_t current = 0;
  for (int i = 0; i < kCycles; ++i) {
    std::size_t next = (current + 3 + std::size_t(i % 3)) % frames.size();
    if (next == current) next = (next + 1) % frames.size();
    order.push_back(current = next);
  }

  const vk::Config config;  // framesInFlight 2
  const std::uint32_t recordsPerCycle = 1 + config.framesInFlight;

  // The driver alone: ao_sample dispatched at the same sizes in the same order, as often.
  double rawGrowth = 0;
  {
    std::vector<std::unique_ptr<RawAoSample>> raws;
    for (const auto& f : frames) raws.push_back(std::make_unique<RawAoSample>(kSettings, f.camera));
    rawGrowth = baselineGrowth(kWarmup, kCycles, [&](int i) {
      for (std::uint32_t r = 0; r < recordsPerCycle; ++r) raws[order[i]]->dispatch();
    });
  }

  const vk::MemoryStats before = vk::processMemoryStats();
  const auto hostBefore = gHost.snapshot();
  std::unique_ptr<vk::Effect> effect;
  ASSERT_TRUE(vk::Effect::create(countedContext(), config, effect).ok());
  std::map<std::size_t, std::pair<std::uint64_t, std::uint64_t>> perSize;  // device, host bytes when first seen
  const auto resizes = [&](RssHalves& rss) {
    for (int i = 0; i < kCycles; ++i) {
      const std::size_t k = order[i];
      const std::uint64_t plans = effect->plans();
      for (std::uint32_t r = 0; r < recordsPerCycle; ++r) {
        const Status recorded = recordAndSubmit(*effect, frames[k]);
        ASSERT_TRUE(recorded.ok()) << recorded.message;
        ASSERT_EQ(effect->output().extent, sizes[k]);
        ASSERT_EQ(effect->plans(), plans + 1) << "one plan for the resize, none for the records after it";
      }
      const vk::MemoryStats mine = effect->memoryStats();
      const vk::MemoryStats all = vk::processMemoryStats();
      const std::uint64_t host = gHost.snapshot().first;
      const auto [it, first] = perSize.emplace(k, std::make_pair(mine.liveBytes, host));
      ASSERT_EQ(mine.liveBytes, it->second.first) << "device memory, resize " << i << " to size #" << k;
      ASSERT_EQ(host, it->second.second) << "host memory of the Vulkan objects, resize " << i << " to size #" << k;
      ASSERT_GE(mine.liveBytes, effect->plan().totalBytes);
      ASSERT_EQ(all.liveAllocations, before.liveAllocations + mine.liveAllocations) << "resize " << i;
      ASSERT_EQ(all.liveBytes, before.liveBytes + mine.liveBytes) << "resize " << i;
      rss.afterCycle(i);
      if (i % 50 == 49) expectNoMessages(("by resize " + std::to_string(i)).c_str());
    }
    rss.atEnd();
  };
  const RssGrowth rss = expectRssGrowthWithin(rawGrowth, kWarmup, kCycles, "resizes", resizes);
  if (HasFatalFailure()) return;
  const vk::MemoryStats mine = effect->memoryStats();
  std::printf("%d resizes over %zu sizes (%u records each): the effect holds %llu bytes of device memory in %llu "
              "allocations at the end, the same bytes every time a size comes back, and the same host memory for its "
              "Vulkan objects; RSS growth over resizes %d..%d %+.3f MiB (twice the smaller half; end minus warm-up "
              "%+.3f)%s, plain-Vulkan baseline (ao_sample at the same sizes, as often) %+.3f MiB\n",
              kCycles, frames.size(), recordsPerCycle, (unsigned long long)mine.liveBytes,
              (unsigned long long)mine.liveAllocations,
              kWarmup, kCycles, mib(rss.growth), mib(rss.endMinusWarm), rss.note.c_str(), mib(rawGrowth));
  effect.reset();
  EXPECT_EQ(vk::processMemoryStats().liveBytes, before.liveBytes);
  EXPECT_EQ(vk::processMemoryStats().liveAllocations, before.liveAllocations);
  EXPECT_EQ(gHost.snapshot(), hostBefore);
  for (auto& f : frames) context().destroy(f.image);
}

// 1,000 cycles of create -> record (one size: the first plan) -> record (another size: a resize)
// -> destroy. Every cycle ends with a queue submission, as an application's next frame would:
// lavapipe (22.3) defers the destruction of pipelines to the next vkQueueSubmit, so without one the
// memory of every destroyed pipeline (about 300 KB each, the same with plain Vulkan) piles up until
// the device goes. Every kSubmitEvery cycles the two records are submitted (JIT-compiling new
// pipelines, whose code lavapipe keeps); the other cycles record both into a command buffer that is
// never submitted (begun again by the next such cycle), which plans and allocates as a frame does. The plain-Vulkan baseline creates and destroys the same
// number of pipelines a cycle, dispatches as often and submits every cycle. Checked: device memory
// and the host memory of the effect's Vulkan objects come back exactly after every destroy; RSS
// grows at most kAllowedGrowth beyond the baseline.
TEST_F(VkLifetime, CreateResizeDestroy1000Times) {
  // Under the sanitizers RSS is not checked, so the cycles past the exact per-cycle counters only
  // cost time there (4x an uninstrumented run): 250 keep every check of the loop, at a quarter.
  const int longCycles = sanitized() ? 250 : 1000;
  constexpr int kLongWarmup = 100, kSubmitEvery = 25;
  Uploaded small = upload(32, 18), large = upload(56, 30);
  const vk::Config config;
  auto nextFrame = [] { ASSERT_TRUE(context().submit([](VkCommandBuffer) {}).ok()); };
  // The command buffer of the cycles that are not submitted: recorded, ended, never submitted.
  VkCommandBuffer unsubmitted = VK_NULL_HANDLE;
  ASSERT_TRUE(context().allocateCommandBuffers(&unsubmitted, 1).ok());
  struct FreeCommandBuffer {
    VkCommandBuffer& cmd;
    ~FreeCommandBuffer() { vkFreeCommandBuffers(context().device(), context().commandPool(), 1, &cmd); }
  } freeCommandBuffer{unsubmitted};
  const auto recordUnsubmitted = [&](vk::Effect& e, const Uploaded& u) {
    const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    EXPECT_EQ(vkBeginCommandBuffer(unsubmitted, &begin), VK_SUCCESS);
    const Status st = e.record(unsubmitted, u.camera, kSettings, inputsOf(u));
    EXPECT_EQ(vkEndCommandBuffer(unsubmitted), VK_SUCCESS);
    return st;
  };

  std::uint32_t pipelinesPerCycle = 0;
  {
    std::unique_ptr<vk::Effect> probe;
    ASSERT_TRUE(vk::Effect::create(context().deviceContext(), config, probe).ok());
    ASSERT_TRUE(recordUnsubmitted(*probe, small).ok());
    ASSERT_TRUE(recordUnsubmitted(*probe, large).ok());
    pipelinesPerCycle = probe->pipelineCount();
  }
  nextFrame();

  double rawGrowth = 0;
  {
    RawAoSample rawA(kSettings, small.camera), rawB(kSettings, large.camera);
    rawGrowth = baselineGrowth(kLongWarmup, longCycles, [&](int i) {
      for (std::uint32_t k = 0; k < pipelinesPerCycle; ++k) rawA.recreatePipeline();
      if (i % kSubmitEvery == 0) {
        rawA.dispatch();
        rawB.recreatePipeline();
        rawB.dispatch();
      }
      nextFrame();
    });
  }

  const vk::MemoryStats before = vk::processMemoryStats();
  const auto hostBefore = gHost.snapshot();
  std::uint64_t bytesA = 0, bytesB = 0;
  int submitted = 0;
  const auto cycles = [&](RssHalves& rss) {
    submitted = 0;
    for (int i = 0; i < longCycles; ++i) {
      const bool submit = i % kSubmitEvery == 0;
      {
        std::unique_ptr<vk::Effect> effect;
        const Status st = vk::Effect::create(countedContext(), config, effect);
        ASSERT_TRUE(st.ok()) << "cycle " << i << ": " << st.message;
        Status recorded = submit ? recordAndSubmit(*effect, small) : recordUnsubmitted(*effect, small);
        ASSERT_TRUE(recorded.ok()) << "cycle " << i << ": " << recorded.message;
        ASSERT_EQ(effect->output().extent, (Extent{32, 18}));
        if (i == 0) bytesA = effect->memoryStats().liveBytes;
        ASSERT_EQ(effect->memoryStats().liveBytes, bytesA) << "cycle " << i;
        // The resize: what the small plan alone used may stay until framesInFlight records follow
        // it (one has), so the bytes are both plans' share; the same every cycle.
        recorded = submit ? recordAndSubmit(*effect, large) : recordUnsubmitted(*effect, large);
        ASSERT_TRUE(recorded.ok()) << "cycle " << i << ": " << recorded.message;
        ASSERT_EQ(effect->output().extent, (Extent{56, 30}));
        ASSERT_EQ(effect->plans(), 2u) << "cycle " << i;
        if (i == 0) bytesB = effect->memoryStats().liveBytes;
        ASSERT_EQ(effect->memoryStats().liveBytes, bytesB) << "cycle " << i;
        if (submit) ++submitted;
      }
      nextFrame();
      expectBackTo(before, hostBefore, i);
      if (::testing::Test::HasFatalFailure()) return;
      rss.afterCycle(i);
      if (i % 250 == 249) expectNoMessages(("by cycle " + std::to_string(i)).c_str());
    }
    rss.atEnd();
  };
  const RssGrowth rss =
      expectRssGrowthWithin(rawGrowth, kLongWarmup, longCycles, "create/resize/destroy cycles", cycles);
  if (HasFatalFailure()) return;
  std::printf("%d create/resize/destroy cycles (%u pipelines, %llu -> %llu bytes of device memory a cycle, back to "
              "%llu live after each; %d cycles recorded and submitted at both sizes): RSS growth over cycles %d..%d "
              "%+.3f MiB (twice the smaller half; end minus warm-up %+.3f)%s, plain-Vulkan baseline (the same "
              "pipeline, dispatch and submit rounds) %+.3f MiB%s\n",
              longCycles, pipelinesPerCycle, (unsigned long long)bytesA, (unsigned long long)bytesB,
              (unsigned long long)before.liveBytes, submitted, kLongWarmup, longCycles, mib(rss.growth),
              mib(rss.endMinusWarm), rss.note.c_str(), mib(rawGrowth),
              sanitized() ? " (RSS not checked under the sanitizers)" : "");
  context().destroy(small.image);
  context().destroy(large.image);
}

}  // namespace
}  // namespace sao::vktest
