// Monte Carlo random walk: paths (photons) per second and scattering events per second,
// on one thread and on all hardware threads, for two of Jensen et al. 2001's media (red
// channel, g = 0 so σs = σs'):
//   skin1:  σs = 0.74,  σa = 0.032 mm^-1,  η = 1.3  (albedo 0.959, ~30 events per path)
//   marble: σs = 2.19,  σa = 0.0021 mm^-1, η = 1.5  (albedo 0.999, ~1500 events per path)
// Each iteration traces the same photon count on one or all threads (4 chunks per
// hardware thread for skin1, 1 for the 50 times costlier marble paths, so every thread
// has work); time is wall-clock. The all-threads run also reports
// `speedup`, its path rate over the one-thread rate measured just before it.
//   ./build-mc/bench/bench_profiles --benchmark_filter=MonteCarlo
#include "profiles/MonteCarlo.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>
#include <thread>

namespace {

using namespace sss::profiles;

const Coefficients kSkin1Red{0.032, 0.74, 0.0, 1.3};
const Coefficients kMarbleRed{0.0021, 2.19, 0.0, 1.5};

int hardware_threads() {
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// Path rate of the one-thread run of each medium, for the speedup counter.
std::map<std::string, double>& single_thread_rate() {
  static std::map<std::string, double> rates;
  return rates;
}

void run(benchmark::State& state, const std::string& medium, const Coefficients& c,
         int threads, int chunks_per_thread) {
  MonteCarloOptions o;
  o.photons = kMonteCarloChunkPhotons * static_cast<std::uint64_t>(chunks_per_thread) *
              static_cast<std::uint64_t>(hardware_threads());
  o.threads = threads;
  o.bin_edges_mm = log_bin_edges(0.01, 100.0, 64);
  std::uint64_t events = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const MonteCarloResult r = run_monte_carlo(c, o);
    events += r.scattering_events;
    seconds += r.seconds;
    benchmark::DoNotOptimize(r.reflectance.total);
  }
  const double paths = static_cast<double>(state.iterations()) * static_cast<double>(o.photons);
  state.SetItemsProcessed(static_cast<int64_t>(paths));
  state.counters["events/s"] =
      benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
  state.counters["events/path"] = static_cast<double>(events) / paths;
  state.counters["threads"] = threads == 1 ? 1 : hardware_threads();
  const double rate = paths / seconds;
  if (threads == 1) {
    single_thread_rate()[medium] = rate;
  } else if (auto it = single_thread_rate().find(medium); it != single_thread_rate().end()) {
    state.counters["speedup"] = rate / it->second;
  }
}

void BM_MonteCarloSkin1Red_1Thread(benchmark::State& s) { run(s, "skin1", kSkin1Red, 1, 4); }
void BM_MonteCarloSkin1Red_AllThreads(benchmark::State& s) { run(s, "skin1", kSkin1Red, 0, 4); }
void BM_MonteCarloMarbleRed_1Thread(benchmark::State& s) { run(s, "marble", kMarbleRed, 1, 1); }
void BM_MonteCarloMarbleRed_AllThreads(benchmark::State& s) {
  run(s, "marble", kMarbleRed, 0, 1);
}

BENCHMARK(BM_MonteCarloSkin1Red_1Thread)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MonteCarloSkin1Red_AllThreads)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MonteCarloMarbleRed_1Thread)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MonteCarloMarbleRed_AllThreads)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
