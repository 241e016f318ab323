#include "progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sao::render {

Progress::Progress(double thresholdSeconds)
    : threshold_(thresholdSeconds),
      period_(thresholdSeconds > 0 ? std::max(thresholdSeconds, 0.1) : 0.5),
      start_(Clock::now()) {
  watcher_ = std::thread([this] { watch(); });
}

Progress::~Progress() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  watcher_.join();
}

void Progress::print(const std::string& line) {
  std::fprintf(stderr, "sao-render: [%.1f s] %s\n", since(start_), line.c_str());
  std::fflush(stderr);
}

void Progress::begin(const std::string& step) {
  end();
  std::lock_guard lock(mutex_);
  step_ = step;
  stepStart_ = Clock::now();
  nextReport_ = stepStart_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(threshold_));
  done_ = -1;
  if (threshold_ == 0) {
    print(step_ + " ...");
    nextReport_ += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_));
  }
  wake_.notify_all();
}

void Progress::fraction(double done) {
  std::lock_guard lock(mutex_);
  const double before = done_;
  done_ = std::clamp(done, 0.0, 1.0);
  // Threshold 0 also reports each tenth done as it is passed: lines that do not depend on how fast
  // the machine is (the tests rely on them).
  if (threshold_ == 0 && !step_.empty() && std::floor(10 * done_) > std::floor(10 * std::max(before, 0.0))) {
    char text[64];
    std::snprintf(text, sizeof text, ": %.0f %% after %.1f s", 100.0 * done_, since(stepStart_));
    print(step_ + text);
  }
}

void Progress::end() {
  std::lock_guard lock(mutex_);
  if (step_.empty()) return;
  const double took = since(stepStart_);
  if (took >= threshold_) {
    char text[64];
    std::snprintf(text, sizeof text, ": done in %.1f s", took);
    print(step_ + text);
  }
  step_.clear();
}

void Progress::watch() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    if (step_.empty()) {
      wake_.wait(lock);
      continue;
    }
    if (Clock::now() < nextReport_) {
      wake_.wait_until(lock, nextReport_);
      continue;
    }
    char text[64];
    if (done_ >= 0) std::snprintf(text, sizeof text, ": %.0f %% after %.1f s", 100.0 * done_, since(stepStart_));
    else std::snprintf(text, sizeof text, ": running for %.1f s", since(stepStart_));
    print(step_ + text);
    nextReport_ = std::max(nextReport_, Clock::now()) +
                  std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_));
  }
}

}  // namespace sao::render
