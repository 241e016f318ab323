// Progress of sao-render's steps on stderr, so a long run is never silent: a step that has run
// longer than a threshold gets a line every `threshold` seconds (0.1 s at the most often) with
// its share done when it reports one, and a line when it ends. Every line starts
// "sao-render: [T s]", T the time since the run started. Threshold 0 announces each step when it
// begins, reports every 0.5 s and each tenth of a step's share done as it is passed.
#pragma once
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace sao::render {

class Progress {
 public:
  explicit Progress(double thresholdSeconds);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void begin(const std::string& step);  // e.g. "tracing the reference"; ends the step before
  void fraction(double done);           // share of the current step done, in [0, 1]; any thread
  void end();                           // the current step is done

 private:
  using Clock = std::chrono::steady_clock;
  double since(Clock::time_point t) const { return std::chrono::duration<double>(Clock::now() - t).count(); }
  void print(const std::string& line);  // with the mutex held
  void watch();

  const double threshold_, period_;
  const Clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string step_;  // empty: no step running
  Clock::time_point stepStart_, nextReport_;
  double done_ = -1;  // < 0: the step reports no share
  bool stop_ = false;
  std::thread watcher_;
};

}  // namespace sao::render
