// Per-pass timing: vkCmdWriteTimestamp after each pass where the queue family has timestamps
// (GpuTimestamps), otherwise one fenced submission per pass around a steady clock (FinishAndClock),
// reported in sao::Timings like the GL backend (one entry per planned pass).
#include <chrono>
#include <string>

#include "effect_impl.h"

namespace sao::vk {

bool familyHasTimestamps(const EffectState& e) { return e.family.timestampValidBits > 0; }

std::uint32_t queriesPerRegion() { return static_cast<std::uint32_t>(gen::passes().size()) + 1; }

Status createQueryPool(const EffectState& e, std::uint32_t framesInFlight, Handle<VkQueryPool>& out) {
  if (!familyHasTimestamps(e)) {
    out.reset();
    return Status::success();
  }
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = (framesInFlight + 1) * queriesPerRegion();  // + the region of measure()
  if (VkResult r = make(e.owner, e.d.vkCreateQueryPool, e.d.vkDestroyQueryPool, info, out); r != VK_SUCCESS)
    return vkError("vkCreateQueryPool", r);
  return Status::success();
}

bool Effect::timestampsSupported() const { return familyHasTimestamps(*impl_); }  // allocates nothing

namespace {

// The times of the plan's passes (for timings(): a new plan's schedule drops lastTimedRegion).
Status readTimestamps(const EffectState& e, std::uint32_t region, bool wait, Timings& out) {
  const std::vector<PlannedPass>& passes = e.plan().passes;
  std::vector<std::uint64_t> t(passes.size() + 1);
  const VkResult r = e.d.vkGetQueryPoolResults(
      e.owner.device, e.queryPool.get(), region * queriesPerRegion(), static_cast<std::uint32_t>(t.size()),
      t.size() * sizeof(std::uint64_t), t.data(), sizeof(std::uint64_t),
      VK_QUERY_RESULT_64_BIT | (wait ? VK_QUERY_RESULT_WAIT_BIT : 0));
  if (r == VK_NOT_READY)
    return Status::error(StatusCode::DriverError,
                         "timestamps not ready: the command buffer of the last record() has not completed");
  if (r != VK_SUCCESS) return vkError("vkGetQueryPoolResults", r);
  const std::uint32_t bits = e.family.timestampValidBits;
  const std::uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  Timings result;
  result.method = TimingMethod::GpuTimestamps;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    const std::uint64_t ticks = ((t[i + 1] & mask) - (t[i] & mask)) & mask;
    const double ms = double(ticks) * e.props.limits.timestampPeriod * 1e-6;
    result.passes.push_back({std::string(gen::pass(passes[i].pass).name), ms});
  }
  out = std::move(result);
  return Status::success();
}

}  // namespace

Status Submitter::init() {
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pi.queueFamilyIndex = e.ctx.queueFamilyIndex;
  if (VkResult r = make(e.owner, e.d.vkCreateCommandPool, e.d.vkDestroyCommandPool, pi, pool); r != VK_SUCCESS)
    return vkError("vkCreateCommandPool", r);
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  if (VkResult r = make(e.owner, e.d.vkCreateFence, e.d.vkDestroyFence, fi, fence); r != VK_SUCCESS)
    return vkError("vkCreateFence", r);
  return Status::success();
}

Status Submitter::begin(VkCommandBuffer& cmd) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool.get();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  if (VkResult r = e.d.vkAllocateCommandBuffers(e.ctx.device, &ai, &cmd); r != VK_SUCCESS)
    return vkError("vkAllocateCommandBuffers", r);
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (VkResult r = e.d.vkBeginCommandBuffer(cmd, &bi); r != VK_SUCCESS) return vkError("vkBeginCommandBuffer", r);
  return Status::success();
}

Status Submitter::submitAndWait(VkQueue queue, VkCommandBuffer cmd, double* ms) {
  if (VkResult r = e.d.vkEndCommandBuffer(cmd); r != VK_SUCCESS) return vkError("vkEndCommandBuffer", r);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  const auto t0 = std::chrono::steady_clock::now();
  const VkFence f = fence.get();
  if (VkResult r = e.d.vkQueueSubmit(queue, 1, &si, f); r != VK_SUCCESS) return vkError("vkQueueSubmit", r);
  const VkResult w = e.d.vkWaitForFences(e.ctx.device, 1, &f, VK_TRUE, 120'000'000'000ull);
  const auto t1 = std::chrono::steady_clock::now();
  if (w != VK_SUCCESS) return vkError("vkWaitForFences", w);
  if (ms) *ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  if (VkResult r = e.d.vkResetFences(e.ctx.device, 1, &f); r != VK_SUCCESS) return vkError("vkResetFences", r);
  return Status::success();
}

Status Effect::timings(Timings& out) const {
  return guarded("sao::vk::Effect::timings()", [&] {
    const EffectState& e = *impl_;
    if (!familyHasTimestamps(e))
      return Status::error(StatusCode::DriverError, "queue family " + std::to_string(e.ctx.queueFamilyIndex) +
                                                        " has no timestamps (timestampValidBits = 0): use measure()");
    if (e.lastTimedRegion < 0)
      return Status::error(StatusCode::InvalidInput, "no record() with Config::timestamps since create() or the last new plan");
    return readTimestamps(e, static_cast<std::uint32_t>(e.lastTimedRegion), false, out);
  });
}

Status Effect::measure(VkQueue queue, const Camera& camera, const Settings& settings, const Inputs& inputs,
                       const OutputImage* userOutput, Timings& out, MeasureMethod method) {
  return guarded("sao::vk::Effect::measure()", [&] {
    EffectState& e = *impl_;
    out = Timings{};
    if (queue == VK_NULL_HANDLE)
      return Status::error(StatusCode::InvalidInput, "measure(): the queue is VK_NULL_HANDLE");
    Submitter sub(e);
    if (Status st = sub.init(); !st) return st;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (Status st = sub.begin(cmd); !st) return st;
    Recording rec{cmd};
    if (method == MeasureMethod::Auto && familyHasTimestamps(e) && e.queryPool) {
      rec.timingRegion = static_cast<int>(e.config.framesInFlight);  // measure()'s own region
      if (Status st = runFrame(e, camera, settings, inputs, userOutput, rec); !st) return st;
      if (Status st = sub.submitAndWait(queue, cmd, nullptr); !st) return st;
      return readTimestamps(e, static_cast<std::uint32_t>(rec.timingRegion), true, out);
    }
    // Fallback: the prologue untimed, then each pass on its own submission (the last one with the
    // exit barrier), timed from vkQueueSubmit to the fence.
    Timings t;
    t.method = TimingMethod::FinishAndClock;
    rec.perPass = &sub;
    rec.queue = queue;
    rec.times = &t;
    if (Status st = runFrame(e, camera, settings, inputs, userOutput, rec); !st) return st;
    out = std::move(t);
    return Status::success();
  });
}

}  // namespace sao::vk
