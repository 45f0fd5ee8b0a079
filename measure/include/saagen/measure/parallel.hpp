// saagen ground-truth renderer: the row-parallel loop (std::thread).
//
// Determinism: every row is computed by the same code from the same inputs whichever thread
// takes it, and each pixel's random numbers depend only on (seed, x, y) (sampling.hpp), so the
// images are bit-identical for any thread count.
#pragma once

#include <functional>

namespace saagen::measure {

// Number of worker threads for a request: `threads` if positive, else
// std::thread::hardware_concurrency() (at least 1).
int resolve_threads(int threads);

// Runs body(row) for every row in [0, rows) on resolve_threads(threads) worker threads, rows
// handed out one at a time from a shared counter. When given, progress(rows_done) is called on
// the calling thread about every 100 ms while the workers run, and once at the end with
// rows_done == rows. The first exception thrown by body is rethrown after all workers stop.
void parallel_rows(int rows, int threads, const std::function<void(int row)>& body,
                   const std::function<void(int rows_done)>& progress = {});

}  // namespace saagen::measure
