// A minimal parallel loop on std::thread. Threads are started per call and
// block (rather than spin) while waiting, so a busy machine — Blender's UI,
// another build — slows the loop down gracefully instead of stalling it.
#pragma once
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace cmaps {

// Calls body(i) for every i in [0, count), in chunks, on up to `threads`
// threads (the caller's included). The first exception thrown is rethrown.
template <class Body>
void parallel_for(size_t count, int threads, const Body& body, size_t chunk = 64) {
  const size_t workers = std::min<size_t>(std::max(1, threads), (count + chunk - 1) / chunk);
  if (workers <= 1) {
    for (size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto run = [&] {
    try {
      for (size_t begin; (begin = next.fetch_add(chunk)) < count;)
        for (size_t i = begin, end = std::min(count, begin + chunk); i < end; ++i) body(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < workers; ++t) pool.emplace_back(run);
  run();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace cmaps
