// R(r) evaluations per second for every analytic model, on Jensen et al. 2001's skin1,
// red channel (σs' = 0.74, σa = 0.032 mm^-1, g = 0, η = 1.3), at 64 radii log-spaced over
// [0.01, 10] mm. The classical dipole is the baseline; compare items_per_second.
//   ./build-models/bench/bench_profiles --benchmark_filter='Model'
#include "profiles/BetterDipole.h"
#include "profiles/Burley.h"
#include "profiles/ClassicalDipole.h"
#include "profiles/Multipole.h"
#include "profiles/PhotonBeamDiffusion.h"

#include <benchmark/benchmark.h>

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

void run(benchmark::State& state, const RadialProfile& p) {
  const std::vector<double> r = radii();
  for (auto _ : state) {
    double sum = 0.0;
    for (double x : r) sum += p.reflectance(x);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(r.size()));
}

void BM_ModelClassicalDipole(benchmark::State& state) { run(state, ClassicalDipole(kSkin1Red)); }
void BM_ModelBetterDipole(benchmark::State& state) { run(state, BetterDipole(kSkin1Red)); }
void BM_ModelBurley(benchmark::State& state) { run(state, Burley(kSkin1Red)); }
// A 5 mm slab (about 4 reduced mean free paths); the cost does not depend on it.
void BM_ModelMultipole10(benchmark::State& state) { run(state, Multipole(kSkin1Red, 5.0, 10)); }

template <BeamSampling S>
void BM_ModelPbd(benchmark::State& state) {
  const PhotonBeamDiffusion p(kSkin1Red, static_cast<int>(state.range(0)), S);
  run(state, p);
}

}  // namespace

BENCHMARK(BM_ModelClassicalDipole);
BENCHMARK(BM_ModelBetterDipole);
BENCHMARK(BM_ModelBurley);
BENCHMARK(BM_ModelMultipole10);
BENCHMARK(BM_ModelPbd<BeamSampling::Exponential>)->RangeMultiplier(2)->Range(4, 64);
BENCHMARK(BM_ModelPbd<BeamSampling::Equiangular>)->RangeMultiplier(2)->Range(4, 64);
BENCHMARK(BM_ModelPbd<BeamSampling::Mis>)->RangeMultiplier(2)->Range(4, 64);
