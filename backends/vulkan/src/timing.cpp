// Per-pass timing: vkCmdWriteTimestamp after each pass where the queue family has timestamps
// (GpuTimestamps), otherwise one fenced submission per pass around a steady clock (FinishAndClock),
// reported in sao::Timings like the GL backend ("mips" covers all its levels).
#include <chrono>
#include <string>

#include "effect_impl.h"

namespace sao::vk {

bool familyHasTimestamps(const Effect::Impl& e) { return e.family.timestampValidBits > 0; }

Status ensureQueryPool(Effect::Impl& e) {
  if (e.queryPool || !familyHasTimestamps(e)) return Status::success();
  e.queriesPerRegion = static_cast<std::uint32_t>(gen::passes().size()) + 1;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = (e.config.framesInFlight + 1) * e.queriesPerRegion;  // + the region of measure()
  if (VkResult r = e.d.vkCreateQueryPool(e.ctx.device, &info, e.ctx.allocator, &e.queryPool); r != VK_SUCCESS)
    return vkError("vkCreateQueryPool", r);
  return Status::success();
}

bool Effect::timestampsSupported() const { return familyHasTimestamps(*impl_); }

namespace {

Status readTimestamps(const Effect::Impl& e, std::uint32_t region, const std::vector<std::string>& passes, bool wait,
                      Timings& out) {
  std::vector<std::uint64_t> t(passes.size() + 1);
  const VkResult r = e.d.vkGetQueryPoolResults(
      e.ctx.device, e.queryPool, region * e.queriesPerRegion, static_cast<std::uint32_t>(t.size()),
      t.size() * sizeof(std::uint64_t), t.data(), sizeof(std::uint64_t),
      VK_QUERY_RESULT_64_BIT | (wait ? VK_QUERY_RESULT_WAIT_BIT : 0));
  if (r == VK_NOT_READY)
    return Status::error(StatusCode::DriverError,
                         "timestamps not ready: the command buffer of the last record() has not completed");
  if (r != VK_SUCCESS) return vkError("vkGetQueryPoolResults", r);
  const std::uint32_t bits = e.family.timestampValidBits;
  const std::uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  out = Timings{};
  out.method = TimingMethod::GpuTimestamps;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    const std::uint64_t ticks = ((t[i + 1] & mask) - (t[i] & mask)) & mask;
    out.passes.push_back({passes[i], double(ticks) * e.props.limits.timestampPeriod * 1e-6});
  }
  return Status::success();
}

// A command pool, command buffers and a fence that clean up after themselves.
struct Submitter {
  const Effect::Impl& e;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  explicit Submitter(const Effect::Impl& impl) : e(impl) {}
  ~Submitter() {
    if (fence) e.d.vkDestroyFence(e.ctx.device, fence, e.ctx.allocator);
    if (pool) e.d.vkDestroyCommandPool(e.ctx.device, pool, e.ctx.allocator);
  }
  Status init() {
    VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pi.queueFamilyIndex = e.ctx.queueFamilyIndex;
    if (VkResult r = e.d.vkCreateCommandPool(e.ctx.device, &pi, e.ctx.allocator, &pool); r != VK_SUCCESS)
      return vkError("vkCreateCommandPool", r);
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    if (VkResult r = e.d.vkCreateFence(e.ctx.device, &fi, e.ctx.allocator, &fence); r != VK_SUCCESS)
      return vkError("vkCreateFence", r);
    return Status::success();
  }
  Status begin(VkCommandBuffer& cmd) {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    if (VkResult r = e.d.vkAllocateCommandBuffers(e.ctx.device, &ai, &cmd); r != VK_SUCCESS)
      return vkError("vkAllocateCommandBuffers", r);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    if (VkResult r = e.d.vkBeginCommandBuffer(cmd, &bi); r != VK_SUCCESS) return vkError("vkBeginCommandBuffer", r);
    return Status::success();
  }
  // Ends, submits and waits; `ms` gets the wall time from submission to the fence.
  Status submitAndWait(VkQueue queue, VkCommandBuffer cmd, double* ms) {
    if (VkResult r = e.d.vkEndCommandBuffer(cmd); r != VK_SUCCESS) return vkError("vkEndCommandBuffer", r);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    const auto t0 = std::chrono::steady_clock::now();
    if (VkResult r = e.d.vkQueueSubmit(queue, 1, &si, fence); r != VK_SUCCESS) return vkError("vkQueueSubmit", r);
    const VkResult w = e.d.vkWaitForFences(e.ctx.device, 1, &fence, VK_TRUE, 120'000'000'000ull);
    const auto t1 = std::chrono::steady_clock::now();
    if (w != VK_SUCCESS) return vkError("vkWaitForFences", w);
    if (ms) *ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    if (VkResult r = e.d.vkResetFences(e.ctx.device, 1, &fence); r != VK_SUCCESS) return vkError("vkResetFences", r);
    return Status::success();
  }
};

}  // namespace

Status Effect::timings(Timings& out) const {
  const Impl& e = *impl_;
  if (!familyHasTimestamps(e))
    return Status::error(StatusCode::DriverError, "queue family " + std::to_string(e.ctx.queueFamilyIndex) +
                                                      " has no timestamps (timestampValidBits = 0): use measure()");
  if (e.lastTimedRegion < 0)
    return Status::error(StatusCode::InvalidInput, "no record() with Config::timestamps since create() or update()");
  return readTimestamps(e, static_cast<std::uint32_t>(e.lastTimedRegion), e.lastTimedPasses, false, out);
}

Status Effect::measure(VkQueue queue, const Inputs& inputs, const OutputImage* userOutput, Timings& out,
                       MeasureMethod method) {
  Impl& e = *impl_;
  out = Timings{};
  if (queue == VK_NULL_HANDLE) return Status::error(StatusCode::InvalidInput, "measure(): the queue is VK_NULL_HANDLE");
  OutputTarget output;
  if (Status st = checkInputs(e, inputs, userOutput, output); !st) return st;
  Submitter sub(e);
  if (Status st = sub.init(); !st) return st;
  const std::uint32_t slot = acquireSlot(e, inputs, output);
  std::vector<std::string> names;
  for (const auto& p : e.plan.passes) names.emplace_back(gen::pass(p.pass).name);

  if (method == MeasureMethod::Auto && familyHasTimestamps(e) && e.queryPool) {
    const int region = static_cast<int>(e.config.framesInFlight);  // measure()'s own region
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (Status st = sub.begin(cmd); !st) return st;
    recordPrologue(e, cmd, output, region);
    for (std::size_t i = 0; i < e.plan.passes.size(); ++i) recordPass(e, cmd, i, slot, output, region);
    recordEpilogue(e, cmd, output);
    if (Status st = sub.submitAndWait(queue, cmd, nullptr); !st) return st;
    return readTimestamps(e, static_cast<std::uint32_t>(region), names, true, out);
  }

  // Fallback: the prologue untimed, then each pass on its own submission (the last one with the
  // epilogue's barrier), timed from vkQueueSubmit to the fence.
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (Status st = sub.begin(cmd); !st) return st;
  recordPrologue(e, cmd, output, -1);
  if (Status st = sub.submitAndWait(queue, cmd, nullptr); !st) return st;
  Timings t;
  t.method = TimingMethod::FinishAndClock;
  for (std::size_t i = 0; i < e.plan.passes.size(); ++i) {
    if (Status st = sub.begin(cmd); !st) return st;
    recordPass(e, cmd, i, slot, output, -1);
    if (i + 1 == e.plan.passes.size()) recordEpilogue(e, cmd, output);
    double ms = 0;
    if (Status st = sub.submitAndWait(queue, cmd, &ms); !st) return st;
    t.passes.push_back({names[i], ms});
  }
  out = std::move(t);
  return Status::success();
}

}  // namespace sao::vk
