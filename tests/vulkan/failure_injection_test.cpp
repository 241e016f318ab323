// sao::vk::Effect keeps its promises when the driver or the host runs out of memory:
//  * every Vulkan call that can fail (vkCreate*, vkAllocateMemory, vkMapMemory, vkBind*Memory,
//    vkAllocateDescriptorSets), failed in turn through an interposed vkGetDeviceProcAddr: create()
//    returns a DriverError naming the call and destroys every object it made; the first record()
//    (the first plan) returns the error, plans nothing and leaves only the pipelines it built (a
//    cache); a record() that plans again (another size, pass list and variant) returns the error
//    and keeps its previous configuration: the same images, memory and output bit for bit;
//  * every heap allocation the library makes itself (operator new called from libsao_vulkan.so's
//    code, replaced in this program), failed in turn with std::bad_alloc inside create(), the first
//    record(), a re-planning record(), timings() and measure(): no exception crosses the API, the
//    Status says "std::bad_alloc", and the effect stays as it was. A record() that keeps the plan
//    allocates nothing, so nothing can fail there.
// Runs under the validation layer with synchronization validation; any message fails the test.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <new>
#include <set>
#include <string>

#include "analytic_scenes.h"
#include "image_compare.h"
#include "library_allocations.h"
#include "vk_support.h"

// ---- The bad_alloc seam: tests/common/library_allocations.h fails the Nth allocation made from
// libsao_vulkan.so's own code. Everything else (the test, gtest, the validation layer, libstdc++'s
// own string code) allocates normally.

namespace sao::vktest {
namespace {

using test::sameBits;

// Finds libsao_vulkan.so's executable segment.
void findLibrary() {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)))
      << "libsao_vulkan.so's code not found";
}

// Runs `call` with the Nth library allocation throwing; true when it did throw.
template <typename Call>
bool withBadAllocAt(long n, Call&& call) {
  test::failLibraryAllocation(n);
  call();
  const bool failed = test::allocationFailed();
  test::failLibraryAllocation(0);
  return failed;
}

void expectBadAlloc(const Status& st) { expectStatus(st, StatusCode::DriverError, "std::bad_alloc"); }

// `call` (returning a Status) with each library allocation in turn throwing until one runs
// through, which must succeed; every throw gives a bad_alloc Status. Returns how many threw.
template <typename Call>
long badAllocEach(Call&& call) {
  long thrown = 0;
  for (long n = 1; n < 10000; ++n) {
    Status st;
    if (!withBadAllocAt(n, [&] { st = call(); })) {
      EXPECT_TRUE(st.ok()) << st.message;
      return thrown;
    }
    ++thrown;
    expectBadAlloc(st);
  }
  ADD_FAILURE() << "never got through";
  return thrown;
}

void printFailed(const char* what, const std::set<std::string>& failed) {
  std::string names;
  for (const auto& f : failed) names += f + " ";
  std::printf("%s: failed in turn at %zu kinds of call: %s\n", what, failed.size(), names.c_str());
}

// ---- The VkResult seam: an interposed vkGetDeviceProcAddr whose functions fail on the Nth call
// when armed, and which counts the objects the library creates and destroys.
struct Injector {
  int failAt = 0;  // 0: disarmed
  int calls = 0;
  std::string failed;  // the call that failed
  long live = 0;       // objects created minus destroyed
  bool failHere(const char* name) {
    if (failAt == 0 || ++calls != failAt) return false;
    failed = name;
    return true;
  }
  void arm(int n) {
    failAt = n;
    calls = 0;
    failed.clear();
  }
};
Injector gInjector;

template <typename Pfn>
struct Failing;
template <typename... A>
struct Failing<VkResult(VKAPI_PTR*)(A...)> {
  static inline VkResult(VKAPI_PTR* real)(A...) = nullptr;
  static inline const char* name = "";
  static inline int objects = 0;  // made by one successful call (the library makes one pipeline a call)
  static VKAPI_ATTR VkResult VKAPI_CALL call(A... a) {
    if (gInjector.failHere(name)) return VK_ERROR_OUT_OF_DEVICE_MEMORY;
    const VkResult r = real(a...);
    if (r == VK_SUCCESS) gInjector.live += objects;
    return r;
  }
};

template <typename Pfn>
struct Counted;
template <typename H>
struct Counted<void(VKAPI_PTR*)(VkDevice, H, const VkAllocationCallbacks*)> {
  static inline void(VKAPI_PTR* real)(VkDevice, H, const VkAllocationCallbacks*) = nullptr;
  static VKAPI_ATTR void VKAPI_CALL call(VkDevice device, H object, const VkAllocationCallbacks* callbacks) {
    if (object != VK_NULL_HANDLE) --gInjector.live;
    real(device, object, callbacks);
  }
};

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL injectingGetDeviceProcAddr(VkDevice device, const char* name) {
#define SAO_FAILING(fn, made)                                                               \
  if (std::strcmp(name, #fn) == 0) {                                                        \
    using W = Failing<PFN_##fn>;                                                            \
    W::real = reinterpret_cast<PFN_##fn>(vkGetDeviceProcAddr(device, name));               \
    W::name = #fn;                                                                          \
    W::objects = made;                                                                      \
    return reinterpret_cast<PFN_vkVoidFunction>(&W::call);                                  \
  }
#define SAO_COUNTED(fn)                                                                     \
  if (std::strcmp(name, #fn) == 0) {                                                        \
    Counted<PFN_##fn>::real = reinterpret_cast<PFN_##fn>(vkGetDeviceProcAddr(device, name)); \
    return reinterpret_cast<PFN_vkVoidFunction>(&Counted<PFN_##fn>::call);                   \
  }
  SAO_FAILING(vkCreateImage, 1)
  SAO_FAILING(vkCreateImageView, 1)
  SAO_FAILING(vkCreateBuffer, 1)
  SAO_FAILING(vkAllocateMemory, 1)
  SAO_FAILING(vkMapMemory, 0)
  SAO_FAILING(vkBindImageMemory, 0)
  SAO_FAILING(vkBindBufferMemory, 0)
  SAO_FAILING(vkCreateSampler, 1)
  SAO_FAILING(vkCreateShaderModule, 1)
  SAO_FAILING(vkCreateDescriptorSetLayout, 1)
  SAO_FAILING(vkCreatePipelineLayout, 1)
  SAO_FAILING(vkCreateComputePipelines, 1)
  SAO_FAILING(vkCreateDescriptorPool, 1)
  SAO_FAILING(vkAllocateDescriptorSets, 0)  // freed with their pool
  SAO_FAILING(vkCreateQueryPool, 1)
  SAO_FAILING(vkCreateCommandPool, 1)
  SAO_FAILING(vkCreateFence, 1)
  SAO_COUNTED(vkDestroyImage)
  SAO_COUNTED(vkDestroyImageView)
  SAO_COUNTED(vkDestroyBuffer)
  SAO_COUNTED(vkFreeMemory)
  SAO_COUNTED(vkDestroySampler)
  SAO_COUNTED(vkDestroyShaderModule)
  SAO_COUNTED(vkDestroyDescriptorSetLayout)
  SAO_COUNTED(vkDestroyPipelineLayout)
  SAO_COUNTED(vkDestroyPipeline)
  SAO_COUNTED(vkDestroyDescriptorPool)
  SAO_COUNTED(vkDestroyQueryPool)
  SAO_COUNTED(vkDestroyCommandPool)
  SAO_COUNTED(vkDestroyFence)
#undef SAO_FAILING
#undef SAO_COUNTED
  return vkGetDeviceProcAddr(device, name);
}

// A depth image and the inputs for one camera.
struct Scene {
  Camera camera;
  DepthImage depth;
  vk::headless::Image image;
  vk::Inputs inputs() const {
    vk::Inputs in;
    in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
    return in;
  }
};

class VkFailureInjection : public VkTest {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    gInjector = Injector{};
    load(vulkanCamera(48, 27, 4), small);
    load(vulkanCamera(56, 30, 6), large);
    config.framesInFlight = 2;
    config.timestamps = true;
    // With the large scene, another size, pass list (no blur) and variant (no z hierarchy): every
    // object a new plan makes.
    otherSettings.blur_radius = 0;
    otherSettings.use_z_hierarchy = false;
  }
  void TearDown() override {
    gInjector.failAt = 0;
    context().destroy(small.image);
    context().destroy(large.image);
    VkTest::TearDown();
  }
  void load(const Camera& camera, Scene& scene) {
    scene.camera = camera;
    scene.depth = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
    const VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    ASSERT_TRUE(context().uploadDepth(scene.depth, VK_FORMAT_D32_SFLOAT, layout, scene.image).ok());
  }
  vk::DeviceContext injecting() const {
    vk::DeviceContext c = context().deviceContext();
    c.getDeviceProcAddr = &injectingGetDeviceProcAddr;
    return c;
  }
  // The small frame (the first plan) and the large one with otherSettings (a new plan).
  Status recordSmall(vk::Effect& e, VkCommandBuffer cmd) { return e.record(cmd, small.camera, settings, small.inputs()); }
  Status recordOther(vk::Effect& e, VkCommandBuffer cmd) {
    return e.record(cmd, large.camera, otherSettings, large.inputs());
  }
  FloatImage runSmall(vk::Effect& e) { return recordAndRead(e, small.camera, settings, small.inputs()); }
  FloatImage runOther(vk::Effect& e) { return recordAndRead(e, large.camera, otherSettings, large.inputs()); }
  // `st` failed at the call the injector failed.
  static void expectInjected(const Status& st) {
    expectStatus(st, StatusCode::DriverError, gInjector.failed);
    EXPECT_NE(st.message.find("VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos) << st.message;
  }
  // The effect still has its small plan (made by `plans` plans), holds `memory` and renders
  // `before` (a record of the small frame, which keeps that plan).
  void expectUnchanged(vk::Effect& e, std::uint64_t plans, const vk::MemoryStats& memory, const FloatImage& before) {
    EXPECT_EQ(e.plans(), plans);
    EXPECT_EQ(e.plan().aoExtent.width, small.camera.width);
    EXPECT_EQ(e.memoryStats().liveBytes, memory.liveBytes);
    EXPECT_EQ(e.memoryStats().liveAllocations, memory.liveAllocations);
    EXPECT_TRUE(sameBits(runSmall(e), before)) << "the effect renders as before the failed call";
    EXPECT_EQ(e.plans(), plans) << "the small frame keeps the plan";
  }
  // After a successful re-plan to the other frame: committed and used.
  void expectOtherCommitted(vk::Effect& e, std::uint64_t plans) {
    EXPECT_EQ(e.plans(), plans + 1) << "the re-plan that got through is committed";
    EXPECT_EQ(e.plan().aoExtent.width, large.camera.width);
    EXPECT_FALSE(runOther(e).data.empty()) << "the re-plan that got through is used";
    EXPECT_EQ(e.plans(), plans + 1);
  }

  // What fails in turn: a Vulkan call through the injector (the calls failed collected in
  // `failed`) or a heap allocation of the library (std::bad_alloc).
  struct Injection {
    bool vulkan;
    std::set<std::string> failed;
    // Runs `call` with the Nth call failing; true when it did.
    bool at(long n, const std::function<void()>& call) {
      if (!vulkan) return withBadAllocAt(n, call);
      gInjector.arm(int(n));
      call();
      gInjector.failAt = 0;
      if (gInjector.failed.empty()) return false;
      failed.insert(gInjector.failed);
      return true;
    }
    void expect(const Status& st) const { vulkan ? expectInjected(st) : expectBadAlloc(st); }
    std::string what(long n) const {
      return vulkan ? "call " + std::to_string(n) + ": " + gInjector.failed : "allocation " + std::to_string(n);
    }
  };

  // create() with each call in turn failing: the Status, `out` empty, every object made so far
  // destroyed and no device memory left. Returns how many failed.
  long createFailingAtEach(Injection& inj) {
    for (long n = 1; n < 10000; ++n) {
      const vk::MemoryStats process = vk::processMemoryStats();
      std::unique_ptr<vk::Effect> e;
      Status st;
      if (!inj.at(n, [&] { st = vk::Effect::create(injecting(), config, e); })) {
        EXPECT_TRUE(st.ok()) << st.message;
        return n - 1;
      }
      SCOPED_TRACE(inj.what(n));
      inj.expect(st);
      EXPECT_FALSE(e);
      EXPECT_EQ(gInjector.live, 0) << "every object made before the failure is destroyed";
      EXPECT_EQ(vk::processMemoryStats().liveAllocations, process.liveAllocations);
    }
    ADD_FAILURE() << "create() never got through";
    return 0;
  }

  // The first record() (the first plan) of a new effect each time, with each call in turn failing:
  // the Status, nothing planned or recorded (the next record in the same command buffer plans), only
  // the pipelines built left (a cache: pipeline, layout and set layout each), no device memory
  // beyond create()'s; nothing left once the effect goes. Returns how many failed.
  long firstRecordFailingAtEach(Injection& inj) {
    for (long n = 1; n < 10000; ++n) {
      std::unique_ptr<vk::Effect> e;
      EXPECT_TRUE(vk::Effect::create(injecting(), config, e).ok());
      if (!e) return 0;
      const long objects = gInjector.live;
      const vk::MemoryStats created = e->memoryStats();
      bool failed = false;
      const Status good = submitRecord([&](VkCommandBuffer cmd) {
        Status st;
        failed = inj.at(n, [&] { st = recordSmall(*e, cmd); });
        if (!failed) return st;
        SCOPED_TRACE(inj.what(n));
        inj.expect(st);
        EXPECT_EQ(e->plans(), 0u) << "nothing planned";
        EXPECT_EQ(gInjector.live, objects + 3 * long(e->pipelineCount()))
            << "only the pipelines built (pipeline, layout, set layout) stay";
        EXPECT_EQ(e->memoryStats().liveAllocations, created.liveAllocations) << "no device memory beyond create()'s";
        EXPECT_EQ(e->memoryStats().liveBytes, created.liveBytes);
        return recordSmall(*e, cmd);  // in the same command buffer: the failed one recorded nothing
      });
      EXPECT_TRUE(good.ok()) << "the next record plans: " << good.message;
      EXPECT_EQ(e->plans(), 1u);
      if (!failed) return n - 1;
      e.reset();
      EXPECT_EQ(gInjector.live, 0) << "every object is destroyed with the effect";
    }
    ADD_FAILURE() << "the first record() never got through";
    return 0;
  }

  // A record() of `e` (which renders `before` from the small frame) that plans again (the other
  // frame), with each call in turn failing: the Status, nothing recorded, the new pipelines alone
  // left (a cache), and the configuration, memory and output kept bit for bit; the one that gets
  // through is committed. Returns how many failed.
  long replanFailingAtEach(Injection& inj, vk::Effect& e, const FloatImage& before) {
    const std::uint64_t plans = e.plans();
    const vk::MemoryStats memory = e.memoryStats();
    const long objects = gInjector.live;
    const std::uint32_t pipelines = e.pipelineCount();
    for (long n = 1; n < 10000; ++n) {
      Status st;
      bool failed = false;
      EXPECT_TRUE(submitRecord([&](VkCommandBuffer cmd) {
                    failed = inj.at(n, [&] { st = recordOther(e, cmd); });
                    return Status::success();
                  }).ok());
      if (!failed) {
        EXPECT_TRUE(st.ok()) << st.message;
        expectOtherCommitted(e, plans);
        return n - 1;
      }
      SCOPED_TRACE(inj.what(n));
      inj.expect(st);
      EXPECT_EQ(gInjector.live, objects + 3 * long(e.pipelineCount() - pipelines))
          << "only the new pipelines (pipeline, layout, set layout) stay";
      expectUnchanged(e, plans, memory, before);
    }
    ADD_FAILURE() << "the re-planning record() never got through";
    return 0;
  }

  Scene small, large;
  vk::Config config;
  Settings settings, otherSettings;
};

// Every fallible Vulkan call of create() (what it makes before any plan: the parameter buffer, the
// sampler, the query pool), failed in turn: the error names it.
TEST_F(VkFailureInjection, CreateFailingAtEveryVulkanCallLeavesNothingBehind) {
  bool timestamps = false;
  {
    std::unique_ptr<vk::Effect> e;
    ASSERT_TRUE(vk::Effect::create(injecting(), config, e).ok());
    timestamps = e->timestampsSupported();
  }
  Injection calls{true};
  createFailingAtEach(calls);
  EXPECT_EQ(gInjector.live, 0);
  printFailed("create()", calls.failed);
  for (const char* call : {"vkCreateBuffer", "vkAllocateMemory", "vkBindBufferMemory", "vkMapMemory", "vkCreateSampler"})
    EXPECT_TRUE(calls.failed.count(call)) << call << " was never called";
  EXPECT_TRUE(!timestamps || calls.failed.count("vkCreateQueryPool")) << "vkCreateQueryPool was never called";
}

// Every fallible Vulkan call of the first record() (images, memory, pipelines, descriptor sets).
TEST_F(VkFailureInjection, FirstRecordFailingAtEveryVulkanCallLeavesNothingBehind) {
  Injection calls{true};
  firstRecordFailingAtEach(calls);
  printFailed("first record()", calls.failed);
  for (const char* call : {"vkCreateImage", "vkCreateImageView", "vkAllocateMemory", "vkBindImageMemory",
                           "vkCreateComputePipelines", "vkCreateDescriptorPool", "vkAllocateDescriptorSets"})
    EXPECT_TRUE(calls.failed.count(call)) << call << " was never called";
}

// Every fallible Vulkan call of a record() that plans again (another size, pass list and variant).
TEST_F(VkFailureInjection, ReplanningRecordFailingAtEveryVulkanCallKeepsThePreviousConfiguration) {
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(injecting(), config, e).ok());
  const FloatImage before = runSmall(*e);
  ASSERT_FALSE(before.data.empty());
  Injection calls{true};
  replanFailingAtEach(calls, *e, before);
  printFailed("re-planning record()", calls.failed);
  // (vkBindImageMemory is called too but never failed here: the binds follow the first
  // vkAllocateMemory, and while the new pipelines were being built, those call numbers were theirs;
  // once the pipelines are cached, the binds take call numbers already tried.)
  for (const char* call : {"vkCreateImage", "vkCreateImageView", "vkAllocateMemory", "vkCreateComputePipelines",
                           "vkCreateDescriptorPool", "vkAllocateDescriptorSets"})
    EXPECT_TRUE(calls.failed.count(call)) << call << " was never called";
  e.reset();
  EXPECT_EQ(gInjector.live, 0);
}

TEST_F(VkFailureInjection, BadAllocInCreateIsAStatus) {
  findLibrary();
  Injection allocations{false};
  const long thrown = createFailingAtEach(allocations);
  std::printf("create(): std::bad_alloc at each of its %ld allocations\n", thrown);
  EXPECT_GT(thrown, 0);
}

TEST_F(VkFailureInjection, BadAllocInTheFirstRecordIsAStatus) {
  findLibrary();
  Injection allocations{false};
  const long thrown = firstRecordFailingAtEach(allocations);
  std::printf("first record(): std::bad_alloc at each of its %ld allocations\n", thrown);
  EXPECT_GT(thrown, 10);
}

// std::bad_alloc at every allocation of a record() that keeps the plan, timings(), measure() and a
// record() that plans again: a Status each time; a failed record() records nothing (a good one
// after it in the same command buffer gives the same bits).
TEST_F(VkFailureInjection, BadAllocInRecordTimingAndReplanIsAStatus) {
  findLibrary();
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(injecting(), config, e).ok());
  const FloatImage before = runSmall(*e);
  const std::uint64_t plans = e->plans();
  const vk::MemoryStats memory = e->memoryStats();

  long thrown = 0;
  for (long n = 1; n < 10000; ++n) {
    Status recorded;
    const Status good = submitRecord([&](VkCommandBuffer cmd) {
      return withBadAllocAt(n, [&] { recorded = recordSmall(*e, cmd); }) ? recordSmall(*e, cmd) : Status::success();
    });
    if (recorded.ok()) break;
    ++thrown;
    expectBadAlloc(recorded);
    EXPECT_TRUE(good.ok()) << good.message;
    EXPECT_TRUE(sameBits(readOutput(*e), before)) << "a failed record() left nothing in the command buffer";
  }
  // A record() that keeps the plan allocates nothing (tests/vulkan/frame_allocation_test.cpp counts
  // it over 100 frames).
  std::printf("record() keeping the plan: std::bad_alloc at each of its %ld allocations\n", thrown);
  EXPECT_EQ(thrown, 0);

  if (e->timestampsSupported()) {
    Timings t;
    thrown = badAllocEach([&] { t = {}; return e->timings(t); });
    EXPECT_EQ(t.passes.size(), e->plan().passes.size());
    std::printf("timings(): std::bad_alloc at each of its %ld allocations\n", thrown);
    EXPECT_GT(thrown, 0);
  }

  for (vk::MeasureMethod method : {vk::MeasureMethod::Auto, vk::MeasureMethod::FenceClock}) {
    Timings t;
    thrown = badAllocEach(
        [&] { return e->measure(context().queue(), small.camera, settings, small.inputs(), nullptr, t, method); });
    std::printf("measure(%s): std::bad_alloc at each of its %ld allocations\n",
                method == vk::MeasureMethod::Auto ? "Auto" : "FenceClock", thrown);
    EXPECT_GT(thrown, 0);
  }
  expectUnchanged(*e, plans, memory, before);

  Injection allocations{false};
  thrown = replanFailingAtEach(allocations, *e, before);
  std::printf("re-planning record(): std::bad_alloc at each of its %ld allocations\n", thrown);
  EXPECT_GT(thrown, 10);
  e.reset();
  EXPECT_EQ(gInjector.live, 0);
}

}  // namespace
}  // namespace sao::vktest
