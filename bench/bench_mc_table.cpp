// The mc-table: what generating it costs against the analog random walk, and what a
// lookup costs against the classical dipole's closed form.
//
// Generator (one thread). generate_mc_table fills every (η, α') node of its grid from one
// walk set (albedo scaling and Fresnel splitting, McTableGenerator.cpp), while
// run_monte_carlo gives one medium per run. Both trace kWalks walks, binned on the
// shipped table's annuli, roulette at 5% of the entry weight (the table's setting):
//   - BM_McTableGenerator: the shipped albedo axis (64 nodes) × η 1.0…1.6 (13 nodes) =
//     832 nodes; counters walks/s and nodes/s (nodes filled per second, each with kWalks
//     walks);
//   - BM_AnalogOneMedium/<1000 α'>: the analog walk at one medium (σt' = 1, η = 1.4);
//     counters walks/s, media/s, and table_speedup = the generator's nodes/s over this
//     media/s (how many times faster the table is than one analog run per node, if every
//     node cost what this medium costs).
// Times are the calling thread's CPU time (see thread_seconds).
// Lookup (skin1 red channel of Jensen et al. 2001: σa = 0.032, σs' = 0.74 mm^-1, η = 1.3):
//   - BM_Lookup_McTable / BM_Lookup_Dipole: R(r) at 64 radii log-spaced over [0.01, 20]
//     reduced mean free paths; ns per evaluation, and cost_vs_dipole for the table;
//   - BM_Construct_McTable / BM_Construct_Dipole: make_profile for the medium (the table's
//     interpolation and reconstruction happen here; the shipped table is parsed before).
//   nice -n 19 build/bench/bench_profiles --benchmark_filter='McTable|AnalogOneMedium|Lookup_|Construct_'
#include "profiles/McTable.h"
#include "profiles/MonteCarlo.h"
#include "profiles/Profile.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <ctime>
#include <limits>
#include <string>
#include <vector>

namespace {

using namespace sss::profiles;

// This thread's CPU time in seconds. Every timed call runs on the calling thread
// (threads = 1 runs the walk inline), and on a shared 2-core machine wall time would
// also count other processes: ratios are taken from CPU time.
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

constexpr std::uint64_t kWalks = 2 * 4096;  // two batches: the fewest the generator takes

McTableOptions generator_options() {
  McTableOptions o = shipped_mc_table_options();
  std::vector<double> eta;
  for (double e : o.eta)
    if (e <= 1.6 + 1e-12) eta.push_back(e);
  o.eta = eta;
  o.photons = kWalks;
  o.chunk_photons = 4096;
  o.threads = 1;
  return o;
}

// The generator's nodes per second, measured by BM_McTableGenerator (run first).
double& generator_nodes_per_second() {
  static double value = 0.0;
  return value;
}

// The generator's seconds per run, from BM_McTableGenerator.
double& generator_seconds() {
  static double value = 0.0;
  return value;
}

void BM_McTableGenerator(benchmark::State& state) {
  const McTableOptions o = generator_options();
  const double nodes = static_cast<double>(o.eta.size() * o.albedo.size());
  double seconds = 0.0;
  for (auto _ : state) {
    const double start = thread_seconds();
    const McTableData t = generate_mc_table(o);
    seconds += thread_seconds() - start;
    benchmark::DoNotOptimize(t.total.data());
  }
  const double runs = static_cast<double>(state.iterations());
  state.counters["walks/s"] = runs * static_cast<double>(kWalks) / seconds;
  state.counters["nodes"] = nodes;
  state.counters["nodes/s"] = runs * nodes / seconds;
  generator_nodes_per_second() = runs * nodes / seconds;
  generator_seconds() = seconds / runs;
}

void BM_AnalogOneMedium(benchmark::State& state) {
  const double albedo = static_cast<double>(state.range(0)) / 1000.0;
  const Coefficients c{1.0 - albedo, albedo, 0.0, 1.4};
  MonteCarloOptions o;
  o.photons = kWalks;
  o.threads = 1;
  o.roulette_weight = 0.05;
  o.bin_edges_mm = shipped_mc_table_options().r_edges;
  double seconds = 0.0;
  for (auto _ : state) {
    const double start = thread_seconds();
    const MonteCarloResult r = run_monte_carlo(c, o);
    seconds += thread_seconds() - start;
    benchmark::DoNotOptimize(r.reflectance.total);
  }
  const double runs = static_cast<double>(state.iterations());
  state.counters["walks/s"] = runs * static_cast<double>(kWalks) / seconds;
  state.counters["media/s"] = runs / seconds;
  if (generator_nodes_per_second() > 0.0)
    state.counters["table_speedup"] = generator_nodes_per_second() / (runs / seconds);
}

// The analog walk at every albedo node of the generator's grid, η = 1.4 (the middle of its
// η range; a higher η costs more, a lower one less), kWalks / 8 walks each: the counter
// grid_speedup = (n_eta × 8 × this time) / the generator's time for the whole grid, i.e.
// how much longer one analog run per node would take than the generator at the same
// walks per node.
void BM_AnalogEveryAlbedoNode(benchmark::State& state) {
  const McTableOptions g = generator_options();
  MonteCarloOptions o;
  o.photons = kWalks / 8;
  o.threads = 1;
  o.roulette_weight = 0.05;
  o.bin_edges_mm = g.r_edges;
  double seconds = 0.0;
  for (auto _ : state) {
    const double start = thread_seconds();
    for (double albedo : g.albedo) {
      const MonteCarloResult r = run_monte_carlo({1.0 - albedo, albedo, 0.0, 1.4}, o);
      benchmark::DoNotOptimize(r.reflectance.total);
    }
    seconds += thread_seconds() - start;
  }
  const double per_run = seconds / static_cast<double>(state.iterations());
  state.counters["media"] = static_cast<double>(g.albedo.size());
  if (generator_seconds() > 0.0)
    state.counters["grid_speedup"] =
        static_cast<double>(g.eta.size()) * 8.0 * per_run / generator_seconds();
}

BENCHMARK(BM_McTableGenerator)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_AnalogOneMedium)
    ->Arg(500)
    ->Arg(900)
    ->Arg(990)
    ->Arg(999)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK(BM_AnalogEveryAlbedoNode)->Unit(benchmark::kMillisecond)->MinTime(1.0);

// ---------------------------------------------------------------------------------------
// Lookup.

const Coefficients kSkin1Red{0.032, 0.74, 0.0, 1.3};
constexpr double kInfinite = std::numeric_limits<double>::infinity();

std::vector<double> radii_mm() {
  std::vector<double> r(64);
  const double mfp = kSkin1Red.mfp_reduced();
  for (std::size_t i = 0; i < r.size(); ++i)
    r[i] = mfp * 0.01 * std::pow(2000.0, static_cast<double>(i) / (r.size() - 1));
  return r;
}

double sweep(const RadialProfile& p, const std::vector<double>& r) {
  double sum = 0.0;
  for (double x : r) sum += p.reflectance(x);
  return sum;
}

// Seconds per dipole evaluation, from BM_Lookup_Dipole (run first).
double& dipole_seconds_per_eval() {
  static double value = 0.0;
  return value;
}

double time_lookup(benchmark::State& state, const RadialProfile& p) {
  const std::vector<double> r = radii_mm();
  const double start = thread_seconds();
  for (auto _ : state) benchmark::DoNotOptimize(sweep(p, r));
  const double s = thread_seconds() - start;
  const double evals = static_cast<double>(state.iterations()) * static_cast<double>(r.size());
  state.counters["ns/eval"] = 1e9 * s / evals;
  state.SetItemsProcessed(static_cast<int64_t>(evals));
  return s / evals;
}

void BM_Lookup_Dipole(benchmark::State& state) {
  const auto p = make_profile(Model::Dipole, kSkin1Red, kInfinite, {});
  dipole_seconds_per_eval() = time_lookup(state, *p);
}

void BM_Lookup_McTable(benchmark::State& state) {
  const auto p = make_profile(Model::McTable, kSkin1Red, kInfinite, {});
  const double s = time_lookup(state, *p);
  if (dipole_seconds_per_eval() > 0.0) state.counters["cost_vs_dipole"] = s / dipole_seconds_per_eval();
}

void construct(benchmark::State& state, Model m) {
  shipped_mc_table();  // parsed once per process, not part of a profile's construction
  for (auto _ : state) benchmark::DoNotOptimize(make_profile(m, kSkin1Red, kInfinite, {}));
}
void BM_Construct_Dipole(benchmark::State& state) { construct(state, Model::Dipole); }
void BM_Construct_McTable(benchmark::State& state) { construct(state, Model::McTable); }

// The first construction of any mc-table profile also parses the compiled-in table.
void BM_ParseShippedTable(benchmark::State& state) {
  const McTableData& t = shipped_mc_table();
  const std::string bytes = serialize_mc_table(t);
  for (auto _ : state) benchmark::DoNotOptimize(parse_mc_table(bytes, "bench").total.data());
  state.counters["MB"] = static_cast<double>(bytes.size()) / 1e6;
}

BENCHMARK(BM_Lookup_Dipole)->MinTime(0.5);
BENCHMARK(BM_Lookup_McTable)->MinTime(0.5);
BENCHMARK(BM_Construct_Dipole)->Unit(benchmark::kMicrosecond)->MinTime(0.5);
BENCHMARK(BM_Construct_McTable)->Unit(benchmark::kMicrosecond)->MinTime(0.5);
BENCHMARK(BM_ParseShippedTable)->Unit(benchmark::kMillisecond)->MinTime(0.5);

}  // namespace
