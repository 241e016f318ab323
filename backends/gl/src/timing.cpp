#include "timing.h"

namespace sao::SAO_GL_NS::detail {

PassTimer::~PassTimer() {
  if (!queries_.empty()) gl_.DeleteQueries(GLsizei(queries_.size()), queries_.data());
}

void PassTimer::beginFrame(bool measure) {
  entries_.clear();
  if (!measure) {
    method_ = TimingMethod::None;
    return;
  }
  method_ = TimingMethod::FinishAndClock;
  if (!gl_.GetQueryObjectui64v) gpuUnusable_ = true;  // ES without EXT_disjoint_timer_query
  if (gpuUnusable_) return;
  GLint bits = 0, active = 0;
  gl_.GetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
  gl_.GetQueryiv(GL_TIME_ELAPSED, GL_CURRENT_QUERY, &active);
  if (bits <= 0) gpuUnusable_ = true;
  else if (active == 0) method_ = TimingMethod::GpuTimestamps;  // else: the caller's query is running
}

void PassTimer::beginPass(std::string_view name) {
  if (method_ == TimingMethod::None) return;
  Entry e;
  e.pass = name;  // a view of the generated pass table's name
  if (method_ == TimingMethod::GpuTimestamps) {
    if (queries_.size() <= entries_.size()) {
      GLuint q = 0;
      gl_.GenQueries(1, &q);
      queries_.push_back(q);
    }
    e.query = queries_[entries_.size()];
    gl_.BeginQuery(GL_TIME_ELAPSED, e.query);
  } else {
    gl_.Finish();
    e.start = std::chrono::steady_clock::now();
  }
  entries_.push_back(std::move(e));
}

void PassTimer::endPass() {
  if (method_ == TimingMethod::None || entries_.empty()) return;
  if (method_ == TimingMethod::GpuTimestamps) {
    gl_.EndQuery(GL_TIME_ELAPSED);
  } else {
    gl_.Finish();
    entries_.back().end = std::chrono::steady_clock::now();
  }
}

bool PassTimer::endFrame(Timings& out) {
  // Storage is reused (clear, not reassign): a timed steady frame allocates nothing either.
  out.passes.clear();
  out.method = method_;
  if (method_ == TimingMethod::None) return true;
  if (method_ == TimingMethod::GpuTimestamps) {
    // With a buffer on GL_QUERY_BUFFER the result would be written into it: unbind it meanwhile.
    GLint queryBuffer = 0;
    if (gl_.hasQueryBuffer) {
      gl_.GetIntegerv(GL_QUERY_BUFFER_BINDING, &queryBuffer);
      if (queryBuffer) gl_.BindBuffer(GL_QUERY_BUFFER, 0);
    }
    // A compute dispatch never takes less than this; smaller results (0, or the 1 ns Mesa's
    // llvmpipe reports for GL_TIME_ELAPSED around compute work) mean the timer does not see it.
    constexpr GLuint64 kLeastPlausibleNs = 100;
    bool zero = false;
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      GLuint64 ns = 0;
      gl_.GetQueryObjectui64v(entries_[i].query, GL_QUERY_RESULT, &ns);
      zero = zero || ns < kLeastPlausibleNs;
      entries_[i].ms = double(ns) * 1e-6;
    }
    if (queryBuffer) gl_.BindBuffer(GL_QUERY_BUFFER, GLuint(queryBuffer));
    if (zero) {
      gpuUnusable_ = true;  // this driver's timer queries do not see compute work
      method_ = TimingMethod::FinishAndClock;
      entries_.clear();
      out.method = method_;
      return false;
    }
  } else {
    for (std::size_t i = 0; i < entries_.size(); ++i)
      entries_[i].ms = std::chrono::duration<double, std::milli>(entries_[i].end - entries_[i].start).count();
  }
  // One entry per pass (a pass of several dispatches sums them).
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    if (!out.passes.empty() && out.passes.back().pass == entries_[i].pass)
      out.passes.back().milliseconds += entries_[i].ms;
    else
      out.passes.push_back({std::string(entries_[i].pass), entries_[i].ms});
  }
  return true;
}

}  // namespace sao::SAO_GL_NS::detail
