// Sum-of-Gaussians fitting cost. The viewer refits on every slider move, so a full RGB
// refit must stay well under 5 ms on one core.
//   (a) BM_FitGaussians/N: fit_gaussians alone on an already sampled target (skin1,
//       better dipole, 96 samples), N = 4, 6, 8.
//   (b) BM_Refit<model>: what a slider move costs: build the RgbProfile from the changed
//       medium, sample it (make_fit_target) and fit 6 Gaussians. The medium alternates
//       between skin1 and skin1 with σa scaled by 1.05 so no work can be reused.
// Counters: ms = milliseconds per fit or refit, of_5ms = that divided by the 5 ms budget.
//   ./build-fit/bench/bench_profiles --benchmark_filter='Fit|Refit'
#include "profiles/GaussianFit.h"
#include "profiles/Presets.h"

#include <benchmark/benchmark.h>

#include <chrono>

namespace {

using namespace sss::profiles;

constexpr double kBudgetMs = 5.0;

Medium skin1(double sigma_a_scale) {
  Medium m = preset_medium(*find_preset("skin1"));
  for (double& a : m.sigma_a) a *= sigma_a_scale;
  return m;
}

void report(benchmark::State& state, double seconds) {
  const double ms = 1e3 * seconds / static_cast<double>(state.iterations());
  state.counters["ms"] = ms;
  state.counters["of_5ms"] = ms / kBudgetMs;
}

void BM_FitGaussians(benchmark::State& state) {
  const FitTarget target = make_fit_target(RgbProfile(Model::BetterDipole, skin1(1.0)));
  FitOptions opt;
  opt.gaussians = static_cast<int>(state.range(0));
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    GaussianFit fit = fit_gaussians(target, opt);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(fit);
  }
  report(state, seconds);
}
BENCHMARK(BM_FitGaussians)->Arg(4)->Arg(6)->Arg(8)->Unit(benchmark::kMillisecond);

template <Model M>
void BM_Refit(benchmark::State& state) {
  const Medium media[2] = {skin1(1.0), skin1(1.05)};
  FitOptions opt;
  opt.gaussians = 6;
  double seconds = 0.0;
  int i = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const RgbProfile profile(M, media[i++ & 1]);
    GaussianFit fit = fit_gaussians(make_fit_target(profile), opt);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(fit);
  }
  report(state, seconds);
}
BENCHMARK(BM_Refit<Model::BetterDipole>)->Name("BM_RefitBetterDipole")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Refit<Model::Dipole>)->Name("BM_RefitDipole")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Refit<Model::Pbd>)->Name("BM_RefitPbd")->Unit(benchmark::kMillisecond);
// mc-table: three table lookups and reconstructions, and its fit at 0.25 mfp resolution
// (96 blurred samples per channel: the radial Bessel-kernel convolution).
BENCHMARK(BM_Refit<Model::McTable>)->Name("BM_RefitMcTable")->Unit(benchmark::kMillisecond);

}  // namespace
