// Private to the runners module.
#pragma once

#include <algorithm>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "slamkit/core/cpu.hpp"

namespace slamkit {

// The batch loop of every Monte Carlo harness (one vehicle: monte_carlo.hpp; a fleet:
// coop_study.hpp).
struct OrderedBatchParams {
  int runs = 1;
  int batch_runs = 64;  // runs held in memory at once
  int threads = 0;      // 0: all the CPUs this process may use (UsableCpuCount)
  // Called with (finished, total) as runs finish, from worker threads one at a time.
  std::function<void(int, int)> progress;
  int first = 0;  // runs [first, runs): a shard's (each run keeps its index and its streams)
};

// Runs run_one(k) for k in [first, runs) in parallel, batch by batch, and hands each result to
// take(k, result) on the calling thread in index order once its batch is done: sums built in
// `take` are the same for any thread count, and memory holds one batch. `run_one` is called from
// worker threads and must not share mutable state between runs. Throws std::invalid_argument for
// runs or batch_runs < 1.
template <class Result, class RunOne, class Take>
void RunInOrderedBatches(const OrderedBatchParams& params, const RunOne& run_one, const Take& take) {
  if (params.runs < 1 || params.first < 0 || params.first >= params.runs) {
    throw std::invalid_argument("Monte Carlo: runs must be >= 1 and first in [0, runs)");
  }
  if (params.batch_runs < 1) throw std::invalid_argument("Monte Carlo: batch_runs must be >= 1");
  const int threads = params.threads > 0 ? params.threads : UsableCpuCount();
  tbb::task_arena arena(std::max(threads, 1));
  std::mutex progress_mutex;
  int finished = 0;
  std::vector<Result> batch;
  const int total = params.runs - params.first;
  for (int first = params.first; first < params.runs; first += params.batch_runs) {
    const int last = std::min(params.runs, first + params.batch_runs);
    batch.assign(static_cast<std::size_t>(last - first), Result{});
    arena.execute([&] {
      tbb::parallel_for(first, last, [&](int k) {
        batch[static_cast<std::size_t>(k - first)] = run_one(k);
        const std::lock_guard lock(progress_mutex);
        ++finished;
        if (params.progress) params.progress(finished, total);
      });
    });
    for (int k = first; k < last; ++k) take(k, std::move(batch[static_cast<std::size_t>(k - first)]));
  }
}

}  // namespace slamkit
