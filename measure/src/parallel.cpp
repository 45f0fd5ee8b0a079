// Row-parallel loop (see parallel.hpp).
#include "saagen/measure/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace saagen::measure {

int resolve_threads(int threads) {
  if (threads > 0) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void parallel_rows(int rows, int threads, const std::function<void(int row)>& body, const std::function<void(int rows_done)>& progress) {
  if (rows <= 0) {
    if (progress) progress(0);
    return;
  }
  const int workers = std::min(resolve_threads(threads), rows);

  std::atomic<int> next_row{0};
  std::atomic<int> rows_done{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex mutex;
  std::condition_variable finished;
  int running = workers;

  auto work = [&] {
    for (;;) {
      if (failed.load(std::memory_order_relaxed)) break;
      const int row = next_row.fetch_add(1);
      if (row >= rows) break;
      try {
        body(row);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!first_error) first_error = std::current_exception();
        failed = true;
        break;
      }
      rows_done.fetch_add(1, std::memory_order_relaxed);
    }
    std::lock_guard<std::mutex> lock(mutex);
    if (--running == 0) finished.notify_all();
  };

  std::vector<std::thread> pool;
  pool.reserve(workers);
  for (int i = 0; i < workers; ++i) pool.emplace_back(work);
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (running > 0) {
      finished.wait_for(lock, std::chrono::milliseconds(100));
      if (progress && running > 0) {
        const int done = rows_done.load(std::memory_order_relaxed);
        lock.unlock();
        progress(done);
        lock.lock();
      }
    }
  }
  for (std::thread& t : pool) t.join();
  if (first_error) std::rethrow_exception(first_error);
  if (progress) progress(rows);
}

}  // namespace saagen::measure
