// Per-pass timings as every backend reports them.
#pragma once
#include <string>
#include <vector>

namespace sao {

enum class TimingMethod {
  None,            // timing was not requested
  GpuTimestamps,   // GL timer queries / Vulkan vkCmdWriteTimestamp
  FinishAndClock,  // a steady clock around each pass, the GPU idle at both ends: glFinish (when the
                   // GL timers return zero, as GL_TIME_ELAPSED does on llvmpipe) or, in Vulkan's
                   // measure(), one fenced submission per pass
  CpuClock,        // the CPU reference: wall time of each pass
};

const char* toString(TimingMethod method);

struct PassTiming {
  std::string pass;       // the pass name from the effect (all its dispatches together)
  double milliseconds = 0;
};

struct Timings {
  // How every pass below was timed: a backend times all passes of one frame the same way. Each
  // method puts a pass's time on that pass (gl_ / vk_timing_attribution_test, run by hand: llvmpipe, zink, lavapipe).
  TimingMethod method = TimingMethod::None;
  std::vector<PassTiming> passes;
  double totalMilliseconds() const {
    double t = 0;
    for (const auto& p : passes) t += p.milliseconds;
    return t;
  }
};

}  // namespace sao
