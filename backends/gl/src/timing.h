// Per-pass timing: GL_TIME_ELAPSED queries where they measure something, otherwise glFinish
// around each pass plus a steady clock. Mesa's llvmpipe returns 0 or 1 ns for GL_TIME_ELAPSED
// around compute dispatches: the first frame in which a pass measures under 100 ns switches this
// effect to the fallback for good (that frame is measured again by clock).
#pragma once
#include <chrono>
#include <string>
#include <string_view>
#include <vector>

#include "gl_functions.h"
#include "sao/timing.h"

namespace sao::SAO_GL_NS::detail {

class PassTimer {
 public:
  explicit PassTimer(const GlFunctions& gl) : gl_(gl) {}
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  // Starts a frame: method None (not measuring), GpuTimestamps (unless known not to work here or a
  // GL_TIME_ELAPSED query of the caller is active, which cannot nest) or FinishAndClock.
  void beginFrame(bool measure);
  TimingMethod method() const { return method_; }
  void beginPass(std::string_view name);
  void endPass();
  // Collects the results into `out`. False when the GPU timers returned a (near) zero duration: the
  // caller then runs the frame again, which this timer measures with FinishAndClock.
  bool endFrame(Timings& out);

 private:
  struct Entry {
    std::string_view pass;  // the generated pass table's name
    GLuint query = 0;
    double ms = 0;
    std::chrono::steady_clock::time_point start, end;
  };
  const GlFunctions& gl_;
  TimingMethod method_ = TimingMethod::None;
  bool gpuUnusable_ = false;
  std::vector<GLuint> queries_;  // pool, grows to the most passes ever timed in a frame
  std::vector<Entry> entries_;
};

}  // namespace sao::SAO_GL_NS::detail
