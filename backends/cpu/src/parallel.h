// A minimal fork-join loop over rows. The result of every index must not depend on which thread
// runs it (each index writes only its own output rows), so any thread count gives the same bits.
#pragma once
#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>
#include <vector>

namespace sao::cpu::detail {

// Calls fn(i) once for every i in [0, count), on up to `threads` threads (the caller's included).
// Indices are handed out one at a time, so uneven rows balance. If a thread cannot be started the
// remaining ones (at least the caller) do its share. The first exception thrown by fn is rethrown
// here after every thread has stopped.
inline void parallelFor(int count, unsigned threads, const std::function<void(int)>& fn) {
  if (count <= 0) return;
  const unsigned n = std::max(1u, std::min(threads, static_cast<unsigned>(count)));
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto worker = [&] {
    try {
      for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) fn(i);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(errorMutex);
      if (!error) error = std::current_exception();
      next.store(count);  // stop handing out work
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

}  // namespace sao::cpu::detail
