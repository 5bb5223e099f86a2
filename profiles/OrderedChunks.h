// Internal: the thread pool behind both Monte Carlo runs (MonteCarlo.cpp and the mc-table
// generator). Chunks of work are claimed in any order by any thread but reduced strictly
// in chunk order, so a run's result depends only on its inputs, never on the thread count
// or the scheduling: every chunk has its own random stream (seed, chunk), and a finished
// chunk waits until every earlier one has been reduced.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace sss::profiles::detail {

// `threads` = 0: every hardware thread (never more threads than chunks). For each thread,
// make_worker() builds its state (allocated once, reused for every chunk it runs) and
// returns a callable work(chunk, Result&) that fills a Result; reduce(const Result&,
// chunks_done) is called under a lock, in chunk order. Finished Results are recycled (a
// run allocates about `threads` of them). The first exception thrown by a worker or by
// reduce stops the run and is rethrown here after every thread has joined.
template <class Result, class MakeWorker, class Reduce>
void run_ordered_chunks(std::uint64_t chunks, int threads, MakeWorker make_worker, Reduce reduce) {
  std::uint64_t n = threads > 0 ? static_cast<std::uint64_t>(threads)
                                : std::max(1u, std::thread::hardware_concurrency());
  n = std::min(n, chunks);
  std::map<std::uint64_t, Result> pending;
  std::vector<Result> spare;
  std::uint64_t next_to_reduce = 0;
  std::atomic<std::uint64_t> next_chunk{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex mutex;

  auto worker = [&] {
    try {
      auto work = make_worker();
      for (;;) {
        const std::uint64_t k = next_chunk.fetch_add(1);
        if (k >= chunks || stop.load()) return;
        Result r;
        {
          std::lock_guard lock(mutex);
          if (!spare.empty()) {
            r = std::move(spare.back());
            spare.pop_back();
          }
        }
        work(k, r);
        std::lock_guard lock(mutex);
        pending.emplace(k, std::move(r));
        for (auto it = pending.find(next_to_reduce); it != pending.end();
             it = pending.find(next_to_reduce)) {
          ++next_to_reduce;
          reduce(static_cast<const Result&>(it->second), next_to_reduce);
          spare.push_back(std::move(it->second));
          pending.erase(it);
        }
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
  };
  std::vector<std::thread> pool;
  try {
    for (std::uint64_t t = 1; t < n; ++t) pool.emplace_back(worker);
  } catch (...) {  // a thread that cannot start: stop the others, then report it
    stop = true;
    for (auto& t : pool) t.join();
    throw;
  }
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace sss::profiles::detail
