// The fork-join loop over rows that the CPU reference and the ray-traced references
// (samples/raytrace) share. The result of every index must not depend on which thread runs it
// (each index writes only its own outputs), so any thread count gives the same bits.
#pragma once
#include <algorithm>
#include <atomic>
#include <concepts>
#include <cstdint>
#include <exception>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace sao::cpu {

// `requested` threads, or one per hardware thread when it is 0 (at least one).
inline unsigned threadCount(unsigned requested) {
  return requested != 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
}

// Calls fn(i) once for every i in [0, count), on up to threadCount(threads) threads (the caller's
// included). Indices are handed out one at a time, so uneven rows balance. If a thread cannot be
// started the remaining ones (at least the caller) do its share. The first exception thrown by fn
// is rethrown here after every thread has stopped; the indices not yet started are skipped.
template <std::integral Index, class Fn>
void parallelFor(Index count, unsigned threads, Fn&& fn) {
  if (std::cmp_less_equal(count, 0)) return;
  const auto total = static_cast<std::uint64_t>(count);
  const auto n = static_cast<unsigned>(std::min<std::uint64_t>(threadCount(threads), total));
  std::atomic<std::uint64_t> next{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto worker = [&] {
    try {
      for (std::uint64_t i = next.fetch_add(1); i < total; i = next.fetch_add(1)) fn(static_cast<Index>(i));
    } catch (...) {
      const std::lock_guard<std::mutex> lock(errorMutex);
      if (!error) error = std::current_exception();
      next.store(total);  // stop handing out work
    }
  };
  std::vector<std::thread> pool;
  try {
    pool.reserve(n - 1);
    for (unsigned t = 1; t < n; ++t) pool.emplace_back(worker);
  } catch (const std::system_error&) {
    // fewer threads than asked for: the ones running (and this one) take over
  } catch (const std::bad_alloc&) {
  }
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace sao::cpu
