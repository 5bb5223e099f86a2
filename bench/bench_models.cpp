// R(r) evaluations per second for every analytic model, on Jensen et al. 2001's skin1,
// red channel (σs' = 0.74, σa = 0.032 mm^-1, g = 0, η = 1.3), at 64 radii log-spaced over
// [0.01, 10] mm. The classical dipole is the baseline, timed once in the same process:
// the counter cost_vs_dipole is this model's time per evaluation over the dipole's.
//   scripts/bench.sh --benchmark_filter='Model'
#include "profiles/BetterDipole.h"
#include "profiles/Burley.h"
#include "profiles/ClassicalDipole.h"
#include "profiles/Multipole.h"
#include "profiles/PhotonBeamDiffusion.h"
#include "profiles/QuantizedDiffusion.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <vector>

namespace {

using namespace sss::profiles;

const Coefficients kSkin1Red{0.032, 0.74, 0.0, 1.3};

std::vector<double> radii() {
  std::vector<double> r(64);
  for (std::size_t i = 0; i < r.size(); ++i)
    r[i] = 0.01 * std::pow(1000.0, static_cast<double>(i) / (r.size() - 1));
  return r;
}

double sweep(const RadialProfile& p, const std::vector<double>& r) {
  double sum = 0.0;
  for (double x : r) sum += p.reflectance(x);
  return sum;
}

// Seconds per evaluation of the classical dipole, measured once per process (~0.2 s).
double dipole_seconds_per_eval() {
  static const double value = [] {
    const ClassicalDipole d(kSkin1Red);
    const std::vector<double> r = radii();
    const auto start = std::chrono::steady_clock::now();
    int sweeps = 0;
    while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(200)) {
      benchmark::DoNotOptimize(sweep(d, r));
      ++sweeps;
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return s / (static_cast<double>(sweeps) * static_cast<double>(r.size()));
  }();
  return value;
}

void run(benchmark::State& state, const RadialProfile& p) {
  const std::vector<double> r = radii();
  const double baseline = dipole_seconds_per_eval();
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) benchmark::DoNotOptimize(sweep(p, r));
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double evals = static_cast<double>(state.iterations()) * static_cast<double>(r.size());
  state.SetItemsProcessed(static_cast<int64_t>(evals));
  state.counters["cost_vs_dipole"] = (s / evals) / baseline;
}

void BM_ModelClassicalDipole(benchmark::State& state) { run(state, ClassicalDipole(kSkin1Red)); }
void BM_ModelBetterDipole(benchmark::State& state) { run(state, BetterDipole(kSkin1Red)); }
void BM_ModelBurley(benchmark::State& state) { run(state, Burley(kSkin1Red)); }
// A 5 mm slab (about 4 reduced mean free paths); the cost does not depend on it.
void BM_ModelMultipole10(benchmark::State& state) { run(state, Multipole(kSkin1Red, 5.0, 10)); }
// Quantized diffusion with the default schedule (one Gaussian per time step: its R(r) is a
// sum of exp, so the cost is the number of terms, reported beside it).
void BM_ModelQd(benchmark::State& state) {
  const QuantizedDiffusion q(kSkin1Red);
  state.counters["gaussians"] = static_cast<double>(q.terms().size());
  run(state, q);
}

template <BeamSampling S>
void BM_ModelPbd(benchmark::State& state) {
  const PhotonBeamDiffusion p(kSkin1Red, static_cast<int>(state.range(0)), S);
  run(state, p);
}

}  // namespace

BENCHMARK(BM_ModelClassicalDipole);
BENCHMARK(BM_ModelBetterDipole);
BENCHMARK(BM_ModelQd);
BENCHMARK(BM_ModelBurley);
BENCHMARK(BM_ModelMultipole10);
BENCHMARK(BM_ModelPbd<BeamSampling::Exponential>)->RangeMultiplier(2)->Range(4, 64);
BENCHMARK(BM_ModelPbd<BeamSampling::Equiangular>)->RangeMultiplier(2)->Range(4, 64);
BENCHMARK(BM_ModelPbd<BeamSampling::Mis>)->RangeMultiplier(2)->Range(4, 64);
