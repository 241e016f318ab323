// sao/cpu/parallel.h, the row loop of the CPU reference and the ray-traced references: every index
// runs exactly once whatever the thread count, and an exception reaches the caller after every
// thread has stopped.
#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "sao/cpu/parallel.h"

namespace {

TEST(Parallel, RunsEveryIndexOnce) {
  for (unsigned threads : {0u, 1u, 3u, 64u}) {
    std::vector<std::atomic<int>> runs(50);
    sao::cpu::parallelFor(std::uint32_t(runs.size()), threads, [&](std::uint32_t i) { ++runs[i]; });
    for (std::size_t i = 0; i < runs.size(); ++i) ASSERT_EQ(runs[i].load(), 1) << i << ", " << threads << " threads";
  }
}

TEST(Parallel, EmptyAndNegativeCountsRunNothing) {
  int runs = 0;
  sao::cpu::parallelFor(0, 4, [&](int) { ++runs; });
  sao::cpu::parallelFor(-3, 4, [&](int) { ++runs; });
  EXPECT_EQ(runs, 0);
}

TEST(Parallel, RethrowsTheFirstExceptionAfterEveryThreadStops) {
  for (unsigned threads : {1u, 4u}) {
    std::atomic<int> running{0}, started{0};
    auto body = [&](int i) {
      ++running;
      ++started;
      const bool fail = i == 3;
      --running;
      if (fail) throw std::runtime_error("row 3");
    };
    EXPECT_THROW(sao::cpu::parallelFor(1000, threads, body), std::runtime_error) << threads << " threads";
    EXPECT_EQ(running.load(), 0) << "a thread still ran after the rethrow, " << threads << " threads";
    // On one thread the order is known: rows 0 to 3 ran, then no more were handed out.
    if (threads == 1) {
      EXPECT_EQ(started.load(), 4);
    }
  }
}

TEST(Parallel, ThreadCountZeroMeansTheHardware) {
  EXPECT_EQ(sao::cpu::threadCount(5), 5u);
  EXPECT_GE(sao::cpu::threadCount(0), 1u);
}

}  // namespace
