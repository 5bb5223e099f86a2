#include "profiles/MonteCarlo.h"

#include "profiles/MonteCarloWalker.h"
#include "profiles/OrderedChunks.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

namespace sss::profiles {

namespace {

using detail::ChunkSums;
using detail::Walker;

constexpr double kInf = std::numeric_limits<double>::infinity();

[[noreturn]] void fail(const std::string& field, const std::string& why) {
  throw std::invalid_argument(field + ": " + why);
}

// The options' checks; `layered`: for run_layered_monte_carlo, whose layers give the
// thicknesses (thickness_mm must stay at infinity). The order of the checks is that of the
// documented errors (the first bad field is reported).
void validate_options(const MonteCarloOptions& o, bool layered) {
  if (o.photons == 0) fail("photons", "must be > 0");
  if (o.threads < 0) fail("threads", "must be >= 0 (0: all hardware threads)");
  if (layered) {
    if (o.thickness_mm != kInf)
      fail("thickness_mm", "must be left at infinity (its default) for run_layered_monte_carlo: the "
                           "layers give the thicknesses, got " + message_number(o.thickness_mm));
  } else if (!(o.thickness_mm > 0.0)) {
    fail("thickness_mm", "must be > 0 mm (or infinity)");
  }
  if (o.bin_edges_mm.size() == 1) fail("bin_edges_mm", "a single edge bounds no bin");
  for (std::size_t i = 0; i < o.bin_edges_mm.size(); ++i) {
    const double e = o.bin_edges_mm[i];
    if (!std::isfinite(e) || e < 0.0) fail("bin_edges_mm", "edges must be finite and >= 0");
    if (i > 0 && !(e > o.bin_edges_mm[i - 1]))
      fail("bin_edges_mm", "edges must be strictly ascending (edge " + std::to_string(i) + ")");
  }
  if (!(o.roulette_weight > 0.0 && o.roulette_weight < 1.0))
    fail("roulette_weight", "must lie in (0, 1)");
  if (!(o.roulette_survival > 0.0 && o.roulette_survival < 1.0))
    fail("roulette_survival", "must lie in (0, 1)");
  if (o.max_interactions_per_photon == 0) fail("max_interactions_per_photon", "must be > 0");
  if (o.max_scattering_order < 0) fail("max_scattering_order", "must be >= 0 (0: all)");
  if (o.min_scattering_order < 0)
    fail("min_scattering_order", "must be >= 0 (0: every exit is tallied)");
  if (o.max_scattering_order > 0 && o.min_scattering_order > o.max_scattering_order)
    fail("min_scattering_order", "must not exceed max_scattering_order (" +
                                     std::to_string(o.max_scattering_order) +
                                     ") when that is > 0, got " +
                                     std::to_string(o.min_scattering_order) + ": nothing would be tallied");
  if (!(o.incidence_cos > 0.0 && o.incidence_cos <= 1.0)) fail("incidence_cos", "must lie in (0, 1]");
  if (o.exit_cosine_bins < 0 || o.exit_cosine_bins > 100000)
    fail("exit_cosine_bins", "must lie in [0, 100000] (0: no exit-angle tally)");
}

void validate_stack(const std::vector<Layer>& layers) {
  if (layers.empty()) fail("layers", "must not be empty");
  for (std::size_t k = 0; k < layers.size(); ++k) {
    const std::string name = "layers[" + std::to_string(k) + "].";
    const Layer& l = layers[k];
    if (auto e = l.c.validate()) fail(name + e->field, e->message);
    const bool last = k + 1 == layers.size();
    if (!last && !(l.thickness_mm > 0.0 && std::isfinite(l.thickness_mm)))
      fail(name + "thickness_mm", "must be finite and > 0 mm (only the last layer may be "
                                  "infinitely thick), got " + message_number(l.thickness_mm));
    if (last && !(l.thickness_mm > 0.0))
      fail(name + "thickness_mm", "must be > 0 mm (or infinity: a semi-infinite base), got " +
                                      message_number(l.thickness_mm));
    if (k > 0 && l.c.eta != layers[0].c.eta)
      fail(name + "eta", "must equal layers[0].eta (interfaces between layers are index-matched): got " +
                             message_number(l.c.eta) + ", layers[0].eta is " +
                             message_number(layers[0].c.eta));
  }
}

// Mean and standard error from sums of per-photon contributions x over n photons.
void finish(double sum, double sum_sq, double n, double scale, double& mean, double& se) {
  mean = sum / n * scale;
  if (n < 2.0) {
    se = kInf;
    return;
  }
  const double m2 = std::max(0.0, sum_sq - sum * (sum / n));
  se = std::sqrt(m2 / (n * (n - 1.0))) * scale;
}

// The walk in a validated stack (o.thickness_mm unused): both entry points run it.
MonteCarloResult run_stack(const std::vector<Layer>& layers, const MonteCarloOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t nb = opt.bin_edges_mm.empty() ? 0 : opt.bin_edges_mm.size() - 1;
  const std::size_t nc = static_cast<std::size_t>(opt.exit_cosine_bins);
  const std::size_t slots = 2 * nb + nc;  // Walker: radial bins per face, then exit cosines
  const std::uint64_t chunks =
      (opt.photons + kMonteCarloChunkPhotons - 1) / kMonteCarloChunkPhotons;
  // Chunk sums are added strictly in chunk order (OrderedChunks.h): the result does not
  // depend on the thread count.
  ChunkSums total(slots);
  detail::run_ordered_chunks<ChunkSums>(
      chunks, opt.threads,
      [&] {
        return [&, walker = std::make_shared<Walker>(layers, opt)](std::uint64_t k, ChunkSums& sums) {
          const std::uint64_t count =
              std::min(kMonteCarloChunkPhotons, opt.photons - k * kMonteCarloChunkPhotons);
          sums = ChunkSums(slots);
          walker->run_chunk(k, count, sums);
        };
      },
      [&](const ChunkSums& sums, std::uint64_t done) {
        total.add(sums);
        if (opt.progress) opt.progress(static_cast<double>(done) / chunks);
      });

  MonteCarloResult r;
  r.bin_edges_mm = opt.bin_edges_mm;
  r.photons = opt.photons;
  r.scattering_events = total.events;
  r.truncated_photons = total.truncated;
  const double n = static_cast<double>(opt.photons);
  MonteCarloTally* faces[2] = {&r.reflectance, &r.transmittance};
  for (std::size_t f = 0; f < 2; ++f) {
    MonteCarloTally& t = *faces[f];
    finish(total.total[f], total.total_sq[f], n, 1.0, t.total, t.total_stderr);
    t.value.resize(nb);
    t.stderr_.resize(nb);
    for (std::size_t b = 0; b < nb; ++b) {
      const double r0 = opt.bin_edges_mm[b], r1 = opt.bin_edges_mm[b + 1];
      const double area = std::numbers::pi * (r1 * r1 - r0 * r0);
      finish(total.sum[f * nb + b], total.sum_sq[f * nb + b], n, 1.0 / area, t.value[b],
             t.stderr_[b]);
    }
  }
  MonteCarloTally& by_cos = r.reflectance_by_exit_cosine;
  by_cos.total = r.reflectance.total;
  by_cos.total_stderr = r.reflectance.total_stderr;
  by_cos.value.resize(nc);
  by_cos.stderr_.resize(nc);
  for (std::size_t k = 0; k < nc; ++k)
    finish(total.sum[2 * nb + k], total.sum_sq[2 * nb + k], n, static_cast<double>(nc), by_cos.value[k],
           by_cos.stderr_[k]);
  finish(total.total[2], total.total_sq[2], n, 1.0, r.absorbed, r.absorbed_stderr);
  finish(total.total[3], total.total_sq[3], n, 1.0, r.low_order_exits, r.low_order_exits_stderr);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace

MonteCarloResult run_monte_carlo(const Coefficients& c, const MonteCarloOptions& opt) {
  if (auto e = c.validate()) throw std::invalid_argument(e->what());
  validate_options(opt, false);
  return run_stack({Layer{c, opt.thickness_mm}}, opt);
}

MonteCarloResult run_layered_monte_carlo(const std::vector<Layer>& layers,
                                         const MonteCarloOptions& opt) {
  validate_stack(layers);
  validate_options(opt, true);
  return run_stack(layers, opt);
}

std::vector<double> log_bin_edges(double lo, double hi, int count) {
  if (!(lo > 0.0 && hi > lo && std::isfinite(hi)))
    fail("log_bin_edges", "needs 0 < lo < hi, both finite");
  if (count < 1) fail("log_bin_edges", "needs count >= 1");
  std::vector<double> edges{0.0};
  const double step = std::log(hi / lo) / count;
  for (int i = 0; i < count; ++i) edges.push_back(lo * std::exp(step * i));
  edges.push_back(hi);
  return edges;
}

}  // namespace sss::profiles
