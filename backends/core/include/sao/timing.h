// Per-pass timings as every backend reports them.
#pragma once
#include <string>
#include <vector>

namespace sao {

enum class TimingMethod {
  None,            // timing was not requested
  GpuTimestamps,   // GL timer queries / Vulkan vkCmdWriteTimestamp
  FinishAndClock,  // glFinish / fence wait around each pass plus a steady clock (when the GPU
                   // timers return zero, as GL_TIME_ELAPSED does on llvmpipe)
  CpuClock,        // the CPU reference: wall time of each pass
};

const char* toString(TimingMethod method);

struct PassTiming {
  std::string pass;       // the pass name from the effect ("mips" covers all its levels)
  double milliseconds = 0;
};

struct Timings {
  TimingMethod method = TimingMethod::None;
  std::vector<PassTiming> passes;
  double totalMilliseconds() const {
    double t = 0;
    for (const auto& p : passes) t += p.milliseconds;
    return t;
  }
};

}  // namespace sao
