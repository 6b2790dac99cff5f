// Work split into parts run on several threads. Each part writes only its own outputs, so a
// result does not depend on how many threads ran it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <vector>

// A bare-metal standard library (the Cortex-M3 firmware's newlib) has no threads: there every
// part runs on the caller's thread.
#if defined(_GLIBCXX_HAS_GTHREADS) || defined(_LIBCPP_VERSION)
#define INTGRID_HAS_THREADS 1
#include <mutex>
#include <thread>
#else
#define INTGRID_HAS_THREADS 0
#endif

namespace intgrid::core {

// The thread count a `--threads N` option asks for: N, or with 0 every core the machine reports
// (1 where it reports none or has no threads), at most 256.
inline int threads_or_every_core(int threads) {
#if INTGRID_HAS_THREADS
  if (threads <= 0)
    return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 256u));
#else
  if (threads <= 0) return 1;
#endif
  return std::min(threads, 256);
}

// Runs part(p) for every p in [0, parts) on at most `threads` threads (the caller's among them;
// threads <= 1 runs them in order on the caller's). The first exception a part throws is rethrown
// once every thread has stopped.
template <class Part>
void run_parts(std::size_t parts, int threads, Part&& part) {
  const auto workers = static_cast<std::size_t>(std::clamp<long long>(threads, 1, 256));
  if (!INTGRID_HAS_THREADS || workers == 1 || parts <= 1) {
    for (std::size_t p = 0; p < parts; ++p) part(p);
    return;
  }
#if INTGRID_HAS_THREADS
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const std::size_t used = std::min(workers, parts);
  // Worker w takes parts w, w + used, ...: a fixed assignment, no shared counter.
  const auto run = [&](std::size_t w) {
    try {
      for (std::size_t p = w; p < parts; p += used) part(p);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(used - 1);
  for (std::size_t w = 1; w < used; ++w) pool.emplace_back(run, w);
  run(0);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
#endif
}

}  // namespace intgrid::core
