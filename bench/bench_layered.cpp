// Model layered (issue 19): what a stack costs to build (the work a material edit does on
// the fit worker) and to evaluate, against the single-slab multipole in the same process.
// A three-layer skin-like stack, red channel: epidermis 0.25 mm (σa 0.3, σs' 8), papillary
// dermis 0.5 mm (σa 0.05, σs' 3), reticular dermis semi-infinite (σa 0.02, σs' 2), η 1.4.
// Counters: build_vs_multipole and eval_vs_multipole are this stack's time over the
// multipole's (Multipole of the 0.75 mm top two layers' first medium, auto pairs).
//   scripts/bench.sh --benchmark_filter='Layered'
#include "profiles/Layered.h"
#include "profiles/Multipole.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace {

using namespace sss::profiles;

constexpr double kInf = std::numeric_limits<double>::infinity();
const std::vector<Layer> kSkin3 = {{{0.3, 8.0, 0.0, 1.4}, 0.25},
                                   {{0.05, 3.0, 0.0, 1.4}, 0.5},
                                   {{0.02, 2.0, 0.0, 1.4}, kInf}};

std::vector<double> radii() {
  std::vector<double> r(64);
  for (std::size_t i = 0; i < r.size(); ++i)
    r[i] = 0.01 * std::pow(1000.0, static_cast<double>(i) / (r.size() - 1));
  return r;
}

template <class F>
double seconds_per_call(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  int n = 0;
  while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(300)) {
    f();
    ++n;
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / n;
}

const Coefficients& slab() { return kSkin3[0].c; }

double multipole_build() {
  static const double s = seconds_per_call(
      [] { benchmark::DoNotOptimize(Multipole(slab(), 0.75, Multipole::kAutoPairs)); });
  return s;
}

double multipole_eval() {
  static const double s = [] {
    const Multipole m(slab(), 0.75, Multipole::kAutoPairs);
    const auto r = radii();
    return seconds_per_call([&] {
             double sum = 0.0;
             for (double x : r) sum += m.reflectance(x);
             benchmark::DoNotOptimize(sum);
           }) /
           static_cast<double>(r.size());
  }();
  return s;
}

void BM_LayeredBuild(benchmark::State& state) {
  const auto coupling = state.range(0) == 0 ? LayerCoupling::Diffusion : LayerCoupling::Adding;
  (void)LayeredProfile(kSkin3, {}, kDefaultModel, coupling);  // the transform matrix, once
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) benchmark::DoNotOptimize(LayeredProfile(kSkin3, {}, kDefaultModel, coupling));
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                   static_cast<double>(state.iterations());
  state.counters["ms"] = 1e3 * s;
  state.counters["build_vs_multipole"] = s / multipole_build();
}

void BM_LayeredEval(benchmark::State& state) {
  const LayeredProfile p(kSkin3, {});
  const auto r = radii();
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    double sum = 0.0;
    for (double x : r) sum += p.reflectance(x);
    benchmark::DoNotOptimize(sum);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                   (static_cast<double>(state.iterations()) * static_cast<double>(r.size()));
  state.counters["eval_vs_multipole"] = s / multipole_eval();
}

// The RGB stack, as the fit worker builds it for a material edit (three channels).
void BM_LayeredBuildRgb(benchmark::State& state) {
  LayerStack stack;
  for (const Layer& l : kSkin3) {
    Medium m = Medium::from_reduced({l.c.sigma_a, l.c.sigma_a * 1.5, l.c.sigma_a * 2.5},
                                    {l.c.sigma_s, l.c.sigma_s, l.c.sigma_s}, l.c.eta);
    m.thickness_mm = l.thickness_mm;
    stack.push_back(m);
  }
  (void)make_layered_rgb_profile(stack);
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) benchmark::DoNotOptimize(make_layered_rgb_profile(stack));
  state.counters["ms"] = 1e3 *
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
      static_cast<double>(state.iterations());
}

}  // namespace

BENCHMARK(BM_LayeredBuild)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LayeredEval);
BENCHMARK(BM_LayeredBuildRgb)->Unit(benchmark::kMillisecond);
