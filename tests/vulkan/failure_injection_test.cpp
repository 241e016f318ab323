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
  FloatImage read(vk::Effect& e) {
    const vk::OutputImage o = e.output();
    FloatImage ao;
    EXPECT_TRUE(context()
                    .readback(o.image, o.format, o.extent, 0, o.layout, e.config().outputDstStages,
                              e.config().outputDstAccess, ao)
                    .ok());
    return ao;
  }
  FloatImage runSmall(vk::Effect& e) {
    Status recorded;
    EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = recordSmall(e, cmd); }).ok());
    EXPECT_TRUE(recorded.ok()) << recorded.message;
    return read(e);
  }
  FloatImage runOther(vk::Effect& e) {
    Status recorded;
    EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = recordOther(e, cmd); }).ok());
    EXPECT_TRUE(recorded.ok()) << recorded.message;
    return read(e);
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

  Scene small, large;
  vk::Config config;
  Settings settings, otherSettings;
};

// Every fallible Vulkan call of create() (what it makes before any plan: the parameter buffer, the
// sampler, the query pool), failed in turn: the error names it, `out` stays empty, every object
// made so far is destroyed and no device memory is left.
TEST_F(VkFailureInjection, CreateFailingAtEveryVulkanCallLeavesNothingBehind) {
  bool timestamps = false;
  {
    std::unique_ptr<vk::Effect> e;
    ASSERT_TRUE(vk::Effect::create(injecting(), config, e).ok());
    timestamps = e->timestampsSupported();
  }
  std::set<std::string> failed;
  for (int n = 1;; ++n) {
    ASSERT_LT(n, 1000) << "create() never got through";
    const vk::MemoryStats process = vk::processMemoryStats();
    std::unique_ptr<vk::Effect> e;
    gInjector.arm(n);
    const Status st = vk::Effect::create(injecting(), config, e);
    gInjector.failAt = 0;
    if (gInjector.failed.empty()) {
      ASSERT_TRUE(st.ok()) << st.message;
      break;
    }
    SCOPED_TRACE("call " + std::to_string(n) + ": " + gInjector.failed);
    failed.insert(gInjector.failed);
    EXPECT_EQ(st.code, StatusCode::DriverError) << st.message;
    EXPECT_NE(st.message.find(gInjector.failed), std::string::npos) << st.message;
    EXPECT_NE(st.message.find("VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos) << st.message;
    EXPECT_FALSE(e);
    EXPECT_EQ(gInjector.live, 0) << "every object made before the failure is destroyed";
    EXPECT_EQ(vk::processMemoryStats().liveAllocations, process.liveAllocations);
  }
  EXPECT_EQ(gInjector.live, 0);
  std::string names;
  for (const auto& f : failed) names += f + " ";
  std::printf("create(): failed in turn at %zu kinds of call: %s\n", failed.size(), names.c_str());
  for (const char* call : {"vkCreateBuffer", "vkAllocateMemory", "vkBindBufferMemory", "vkMapMemory", "vkCreateSampler"})
    EXPECT_TRUE(failed.count(call)) << call << " was never called";
  if (timestamps) {
    EXPECT_TRUE(failed.count("vkCreateQueryPool"));
  }
}

// Every fallible Vulkan call of the first record() (the first plan: images, memory, pipelines,
// descriptor sets), failed in turn on a new effect each time: the error names it, nothing is
// planned or recorded, every object the plan made is destroyed but the pipelines it built (a
// cache: pipeline, layout and set layout each), no device memory beyond create()'s is left, and
// the next record plans. Destroying the effect then leaves nothing.
TEST_F(VkFailureInjection, FirstRecordFailingAtEveryVulkanCallLeavesNothingBehind) {
  std::set<std::string> failed;
  for (int n = 1;; ++n) {
    ASSERT_LT(n, 1000) << "the first record() never got through";
    std::unique_ptr<vk::Effect> e;
    ASSERT_TRUE(vk::Effect::create(injecting(), config, e).ok());
    const long objects = gInjector.live;
    const vk::MemoryStats created = e->memoryStats();
    Status st, good;
    long left = 0;
    std::uint32_t pipelines = 0;
    std::uint64_t plansAfterFailure = 0;
    vk::MemoryStats afterFailure;
    ASSERT_TRUE(context()
                    .submit([&](VkCommandBuffer cmd) {
                      gInjector.arm(n);
                      st = recordSmall(*e, cmd);
                      gInjector.failAt = 0;
                      if (gInjector.failed.empty()) return;
                      left = gInjector.live;
                      pipelines = e->pipelineCount();
                      plansAfterFailure = e->plans();
                      afterFailure = e->memoryStats();
                      good = recordSmall(*e, cmd);  // in the same command buffer: the failed one recorded nothing
                    })
                    .ok());
    if (gInjector.failed.empty()) {
      ASSERT_TRUE(st.ok()) << st.message;
      EXPECT_EQ(e->plans(), 1u);
      break;
    }
    SCOPED_TRACE("call " + std::to_string(n) + ": " + gInjector.failed);
    failed.insert(gInjector.failed);
    EXPECT_EQ(st.code, StatusCode::DriverError) << st.message;
    EXPECT_NE(st.message.find(gInjector.failed), std::string::npos) << st.message;
    EXPECT_NE(st.message.find("VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos) << st.message;
    EXPECT_EQ(plansAfterFailure, 0u) << "nothing planned";
    EXPECT_EQ(left, objects + 3 * long(pipelines)) << "only the pipelines built (pipeline, layout, set layout) stay";
    EXPECT_EQ(afterFailure.liveAllocations, created.liveAllocations) << "no device memory beyond create()'s";
    EXPECT_EQ(afterFailure.liveBytes, created.liveBytes);
    EXPECT_TRUE(good.ok()) << "the next record plans: " << good.message;
    EXPECT_EQ(e->plans(), 1u);
    e.reset();
    EXPECT_EQ(gInjector.live, 0) << "every object is destroyed with the effect";
  }
  std::string names;
  for (const auto& f : failed) names += f + " ";
  std::printf("first record(): failed in turn at %zu kinds of call: %s\n", failed.size(), names.c_str());
  for (const char* call : {"vkCreateImage", "vkCreateImageView", "vkAllocateMemory", "vkBindImageMemory",
                           "vkCreateComputePipelines", "vkCreateDescriptorPool", "vkAllocateDescriptorSets"})
    EXPECT_TRUE(failed.count(call)) << call << " was never called";
}

// Every fallible Vulkan call of a record() that plans again (another size, pass list and variant),
// failed in turn: the error, nothing recorded, and the effect keeps its configuration, memory and
// output bit for bit. Pipelines built for the new variant stay (a cache); nothing else is left.
TEST_F(VkFailureInjection, ReplanningRecordFailingAtEveryVulkanCallKeepsThePreviousConfiguration) {
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(injecting(), config, e).ok());
  const FloatImage before = runSmall(*e);
  ASSERT_FALSE(before.data.empty());
  const std::uint64_t plans = e->plans();
  const vk::MemoryStats memory = e->memoryStats();
  const long objects = gInjector.live;
  const std::uint32_t pipelines = e->pipelineCount();
  std::set<std::string> failed;
  for (int n = 1;; ++n) {
    ASSERT_LT(n, 1000) << "the re-planning record() never got through";
    Status st;
    ASSERT_TRUE(context()
                    .submit([&](VkCommandBuffer cmd) {
                      gInjector.arm(n);
                      st = recordOther(*e, cmd);
                      gInjector.failAt = 0;
                    })
                    .ok());
    if (gInjector.failed.empty()) {
      ASSERT_TRUE(st.ok()) << st.message;
      break;
    }
    SCOPED_TRACE("call " + std::to_string(n) + ": " + gInjector.failed);
    failed.insert(gInjector.failed);
    EXPECT_EQ(st.code, StatusCode::DriverError) << st.message;
    EXPECT_NE(st.message.find(gInjector.failed), std::string::npos) << st.message;
    EXPECT_EQ(gInjector.live, objects + 3 * long(e->pipelineCount() - pipelines))
        << "only the new pipelines (pipeline, layout, set layout) stay";
    expectUnchanged(*e, plans, memory, before);
  }
  std::string names;
  for (const auto& f : failed) names += f + " ";
  std::printf("re-planning record(): failed in turn at %zu kinds of call: %s\n", failed.size(), names.c_str());
  // (vkBindImageMemory is called too but never failed here: the binds follow the first
  // vkAllocateMemory, and while the new pipelines were being built, those call numbers were theirs;
  // once the pipelines are cached, the binds take call numbers already tried.)
  for (const char* call : {"vkCreateImage", "vkCreateImageView", "vkAllocateMemory", "vkCreateComputePipelines",
                           "vkCreateDescriptorPool", "vkAllocateDescriptorSets"})
    EXPECT_TRUE(failed.count(call)) << call << " was never called";
  expectOtherCommitted(*e, plans);
  e.reset();
  EXPECT_EQ(gInjector.live, 0);
}

// std::bad_alloc at every allocation the library makes in create(): a DriverError, no effect, no
// device memory left.
TEST_F(VkFailureInjection, BadAllocInCreateIsAStatus) {
  findLibrary();
  long thrown = 0;
  for (long n = 1;; ++n) {
    ASSERT_LT(n, 10000);
    const vk::MemoryStats process = vk::processMemoryStats();
    std::unique_ptr<vk::Effect> e;
    Status st;
    if (!withBadAllocAt(n, [&] { st = vk::Effect::create(injecting(), config, e); })) {
      ASSERT_TRUE(st.ok()) << st.message;
      break;
    }
    ++thrown;
    SCOPED_TRACE("allocation " + std::to_string(n));
    EXPECT_EQ(st.code, StatusCode::DriverError) << st.message;
    EXPECT_NE(st.message.find("std::bad_alloc"), std::string::npos) << st.message;
    EXPECT_FALSE(e);
    EXPECT_EQ(gInjector.live, 0) << "every object made before the exception is destroyed";
    EXPECT_EQ(vk::processMemoryStats().liveAllocations, process.liveAllocations);
  }
  std::printf("create(): std::bad_alloc at each of its %ld allocations\n", thrown);
  EXPECT_GT(thrown, 0);
}

// std::bad_alloc at every allocation of the first record() (the first plan), on a new effect each
// time: a DriverError, nothing planned, no device memory beyond create()'s, only the pipelines
// built left (a cache), and the next record plans; nothing is left once the effect goes.
TEST_F(VkFailureInjection, BadAllocInTheFirstRecordIsAStatus) {
  findLibrary();
  long thrown = 0;
  for (long n = 1;; ++n) {
    ASSERT_LT(n, 10000);
    std::unique_ptr<vk::Effect> e;
    ASSERT_TRUE(vk::Effect::create(injecting(), config, e).ok());
    const long objects = gInjector.live;
    const vk::MemoryStats created = e->memoryStats();
    Status st, good;
    bool threw = false;
    ASSERT_TRUE(context()
                    .submit([&](VkCommandBuffer cmd) {
                      threw = withBadAllocAt(n, [&] { st = recordSmall(*e, cmd); });
                      if (!threw) return;
                      SCOPED_TRACE("allocation " + std::to_string(n));
                      EXPECT_EQ(e->plans(), 0u) << "nothing planned";
                      EXPECT_EQ(gInjector.live, objects + 3 * long(e->pipelineCount()))
                          << "only the pipelines built (pipeline, layout, set layout) stay";
                      EXPECT_EQ(e->memoryStats().liveAllocations, created.liveAllocations);
                      EXPECT_EQ(e->memoryStats().liveBytes, created.liveBytes);
                      good = recordSmall(*e, cmd);  // in the same command buffer: the failed one recorded nothing
                    })
                    .ok());
    if (!threw) {
      ASSERT_TRUE(st.ok()) << st.message;
      break;
    }
    ++thrown;
    SCOPED_TRACE("allocation " + std::to_string(n));
    EXPECT_EQ(st.code, StatusCode::DriverError) << st.message;
    EXPECT_NE(st.message.find("std::bad_alloc"), std::string::npos) << st.message;
    EXPECT_TRUE(good.ok()) << "the next record plans: " << good.message;
    EXPECT_EQ(e->plans(), 1u);
    e.reset();
    EXPECT_EQ(gInjector.live, 0) << "every object is destroyed with the effect";
  }
  std::printf("first record(): std::bad_alloc at each of its %ld allocations\n", thrown);
  EXPECT_GT(thrown, 10);
}

// std::bad_alloc at every allocation of a record() that keeps the plan, timings(), measure() and a
// record() that plans again: a Status each time; the re-planning record() keeps the configuration
// and the output bit for bit; a failed record() records nothing (a good one after it in the same
// command buffer gives the same bits).
TEST_F(VkFailureInjection, BadAllocInRecordTimingAndReplanIsAStatus) {
  findLibrary();
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(injecting(), config, e).ok());
  const FloatImage before = runSmall(*e);
  const std::uint64_t plans = e->plans();
  const vk::MemoryStats memory = e->memoryStats();
  auto expectBadAlloc = [](const Status& st) {
    EXPECT_EQ(st.code, StatusCode::DriverError) << st.message;
    EXPECT_NE(st.message.find("std::bad_alloc"), std::string::npos) << st.message;
  };

  long thrown = 0;
  for (long n = 1;; ++n) {
    ASSERT_LT(n, 10000);
    Status recorded, good;
    Status submitted = context().submit([&](VkCommandBuffer cmd) {
      if (withBadAllocAt(n, [&] { recorded = recordSmall(*e, cmd); })) good = recordSmall(*e, cmd);
    });
    ASSERT_TRUE(submitted.ok()) << submitted.message;
    if (recorded.ok()) break;
    ++thrown;
    expectBadAlloc(recorded);
    EXPECT_TRUE(good.ok()) << good.message;
    EXPECT_TRUE(sameBits(read(*e), before)) << "a failed record() left nothing in the command buffer";
  }
  // A record() that keeps the plan allocates nothing (tests/vulkan/frame_allocation_test.cpp counts
  // it over 100 frames).
  std::printf("record() keeping the plan: std::bad_alloc at each of its %ld allocations\n", thrown);
  EXPECT_EQ(thrown, 0);

  if (e->timestampsSupported()) {
    thrown = 0;
    for (long n = 1;; ++n) {
      ASSERT_LT(n, 10000);
      Timings t;
      Status st;
      if (!withBadAllocAt(n, [&] { st = e->timings(t); })) {
        EXPECT_TRUE(st.ok()) << st.message;
        EXPECT_EQ(t.passes.size(), e->plan().passes.size());
        break;
      }
      ++thrown;
      expectBadAlloc(st);
    }
    std::printf("timings(): std::bad_alloc at each of its %ld allocations\n", thrown);
    EXPECT_GT(thrown, 0);
  }

  for (vk::MeasureMethod method : {vk::MeasureMethod::Auto, vk::MeasureMethod::FenceClock}) {
    thrown = 0;
    for (long n = 1;; ++n) {
      ASSERT_LT(n, 10000);
      Timings t;
      Status st;
      if (!withBadAllocAt(n, [&] {
            st = e->measure(context().queue(), small.camera, settings, small.inputs(), nullptr, t, method);
          })) {
        EXPECT_TRUE(st.ok()) << st.message;
        break;
      }
      ++thrown;
      expectBadAlloc(st);
    }
    std::printf("measure(%s): std::bad_alloc at each of its %ld allocations\n",
                method == vk::MeasureMethod::Auto ? "Auto" : "FenceClock", thrown);
    EXPECT_GT(thrown, 0);
  }
  expectUnchanged(*e, plans, memory, before);

  thrown = 0;
  const long objects = gInjector.live;
  const std::uint32_t pipelines = e->pipelineCount();
  for (long n = 1;; ++n) {
    ASSERT_LT(n, 10000);
    Status st;
    bool threw = false;
    ASSERT_TRUE(
        context().submit([&](VkCommandBuffer cmd) { threw = withBadAllocAt(n, [&] { st = recordOther(*e, cmd); }); }).ok());
    if (!threw) {
      ASSERT_TRUE(st.ok()) << st.message;
      break;
    }
    ++thrown;
    SCOPED_TRACE("allocation " + std::to_string(n));
    expectBadAlloc(st);
    EXPECT_EQ(gInjector.live, objects + 3 * long(e->pipelineCount() - pipelines))
        << "only the new pipelines (pipeline, layout, set layout) stay";
    expectUnchanged(*e, plans, memory, before);
  }
  std::printf("re-planning record(): std::bad_alloc at each of its %ld allocations\n", thrown);
  EXPECT_GT(thrown, 10);
  expectOtherCommitted(*e, plans);
  e.reset();
  EXPECT_EQ(gInjector.live, 0);
}

}  // namespace
}  // namespace sao::vktest
