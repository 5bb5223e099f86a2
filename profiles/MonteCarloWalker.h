// Internal to run_monte_carlo and run_layered_monte_carlo (MonteCarlo.cpp): the per-photon
// random walk in a stack of layers that MonteCarlo.h describes (a single medium is the
// stack of one layer), and the per-chunk sums it tallies into.
#pragma once

#include "profiles/Medium.h"
#include "profiles/MonteCarlo.h"
#include "profiles/Random.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sss::profiles::detail {

// Per-chunk sums of per-photon contributions. Bins [0, nb) are reflectance, [nb, 2nb)
// transmittance, [2nb, 2nb + nc) the top face's exits by outside cosine. Totals: 0
// reflectance, 1 transmittance, 2 absorbed, 3 exits below min_scattering_order.
inline constexpr int kChunkTotals = 4;
struct ChunkSums {
  std::vector<double> sum, sum_sq;
  double total[kChunkTotals] = {0, 0, 0, 0};
  double total_sq[kChunkTotals] = {0, 0, 0, 0};
  std::uint64_t events = 0;
  std::uint64_t truncated = 0;

  explicit ChunkSums(std::size_t slots = 0) : sum(slots, 0.0), sum_sq(slots, 0.0) {}
  void add(const ChunkSums& o) {
    for (std::size_t i = 0; i < sum.size(); ++i) {
      sum[i] += o.sum[i];
      sum_sq[i] += o.sum_sq[i];
    }
    for (int k = 0; k < kChunkTotals; ++k) {
      total[k] += o.total[k];
      total_sq[k] += o.total_sq[k];
    }
    events += o.events;
    truncated += o.truncated;
  }
};

// One worker's walker: the per-photon dense accumulator and its list of touched slots are
// allocated once and reused, so a photon allocates nothing.
class Walker {
 public:
  // `layers`: a valid stack, top first (MonteCarlo.cpp validates it); its last layer's
  // thickness may be infinite. o.thickness_mm is not used. Both must outlive the walker.
  Walker(const std::vector<Layer>& layers, const MonteCarloOptions& o);
  // Walks `count` photons on the RNG stream (o.seed, chunk) and adds their per-photon
  // contributions, and their squares, to `out`.
  void run_chunk(std::uint64_t chunk, std::uint64_t count, ChunkSums& out);

 private:
  // Adds the weight w leaving through `face` (0 top, 1 bottom) at radius r to this
  // photon's bin, if r lies within the bin edges.
  void tally(std::size_t face, double r, double w);
  // Adds the weight w leaving the top face with inside cosine cos_inside to its exit-cosine
  // bin (MonteCarloOptions::exit_cosine_bins), by the refracted outside cosine.
  void tally_exit_cosine(double cos_inside, double w);
  void add(std::size_t slot, double w);
  // One photon: adds what it leaves through the top face, the bottom face, what is
  // absorbed and what leaves below min_scattering_order to totals[0], [1], [2] and [3],
  // and its (tallied) exits to its bins.
  void walk(Xoshiro256ss& rng, double totals[kChunkTotals], ChunkSums& out);
  // Turns the unit direction u by a Henyey–Greenstein scattering event.
  static void scatter(Xoshiro256ss& rng, double g, double& ux, double& uy, double& uz);

  const std::vector<Layer>& layers_;
  const MonteCarloOptions& o_;
  std::vector<double> bottom_;  // z of layer k's bottom face (infinity for a semi-infinite base)
  bool scatters_;               // some layer has sigma_s > 0: flights draw an optical depth
  std::size_t nb_, nc_;
  std::vector<double> photon_;
  std::vector<std::size_t> touched_;
};

}  // namespace sss::profiles::detail
