// Monte Carlo reference: an analog-direction random walk with Henyey–Greenstein
// scattering in a stack of layers under a smooth dielectric boundary (Fresnel reflection
// and refraction, total internal reflection). A single medium, semi-infinite or a finite
// slab (run_monte_carlo), is the stack of one layer; run_layered_monte_carlo takes several.
//
// The stack (profiles/Layered.h): layers top first, z pointing down from the lit face at
// z = 0; layer k has its own sigma_a, sigma_s and g and spans [z_k, z_k + thickness_k).
// Every layer but the last is finite; the last may be infinitely thick (a semi-infinite
// base). All layers share one eta, so the interfaces between layers are index-matched: a
// photon crosses them without reflection or refraction and flies on with the next
// layer's coefficients. The top face, and the bottom face of a stack whose last layer is
// finite, are smooth dielectric boundaries to the outside with that eta.
//
// A unit-power pencil beam enters at the origin at normal incidence; like the diffusion
// models, results are per unit power that entered (the specular reflection at entry is
// excluded). Deterministic for a seed whatever the thread count: photons are processed in
// fixed chunks, each with its own RNG stream, and chunk tallies are summed in order.
// Every binned value carries its standard error, computed from per-photon contributions.
//
// The walk (MonteCarloWalker.cpp has the details and sources):
// - photons start at the origin going straight down (+z; the medium is z >= 0), or along
//   the refracted beam of MonteCarloOptions::incidence_cos, with
//   weight 1; distances between scattering events are sampled with sigma_s, and the weight
//   decays continuously as exp(-sigma_a * path length) ("absorption weighting", the
//   microscopic Beer–Lambert form; Sassaroli & Martelli 2012, JOSA A 29(10):2110, show it
//   equals implicit capture with sigma_t flights in expectation). Without scattering the
//   walk is therefore deterministic and reproduces the slab's closed forms to rounding;
// - in a stack, a flight samples its optical depth tau = -ln(1 - u) once and spends it
//   layer by layer: a flight that reaches an interface before its scattering event
//   carries the remaining depth tau - sigma_s_k * (path in layer k) into the next layer
//   (a layer with sigma_s = 0 spends none: the flight crosses it), and the weight decays
//   as exp(-sum_k sigma_a_k * path in layer k). This is the exact free-path distribution
//   of a piecewise-constant medium (the survival probability is exp(-integral of
//   sigma_s along the path)), and a layer split into two identical ones walks the same
//   path up to rounding;
// - Henyey–Greenstein scattering with the real g (not similarity-reduced) of the layer
//   where the event happens;
// - Russian roulette (unbiased) below `roulette_weight`;
// - Fresnel splitting at each outer face: the fraction 1 - Fr of the weight escapes and is
//   tallied at the exit radius; the fraction Fr reflects specularly and walks on.
#pragma once

#include "profiles/Medium.h"

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace sss::profiles {

struct MonteCarloOptions {
  std::uint64_t photons = 1u << 20;
  std::uint64_t seed = 1;
  int threads = 0;  // 0: std::thread::hardware_concurrency()
  // run_monte_carlo's slab thickness (infinity: semi-infinite). run_layered_monte_carlo
  // takes the thicknesses from its layers and refuses anything but the default here.
  double thickness_mm = std::numeric_limits<double>::infinity();
  // Radial bin edges (mm, ascending, first edge may be 0). Exits beyond the last edge
  // count in the totals only.
  std::vector<double> bin_edges_mm;
  // Called with the fraction done (0..1] after each chunk; may be empty. Calls come from
  // worker threads but never overlap, and the fractions increase. An exception thrown by
  // it stops the run and is rethrown by run_monte_carlo (run_layered_monte_carlo).
  std::function<void(double)> progress;

  // Russian roulette: when a photon's weight falls below roulette_weight it survives with
  // probability roulette_survival (its weight divided by that) or ends. In (0, 1) each.
  double roulette_weight = 1e-4;
  double roulette_survival = 0.1;
  // Guard against endless walks: a photon is stopped after this many interactions
  // (scattering events plus boundary hits); such photons are counted in
  // MonteCarloResult::truncated_photons and their remaining weight is lost.
  std::uint64_t max_interactions_per_photon = 1'000'000;
  // 0: every scattering order. k > 0: a photon ends (its weight dropped, not tallied)
  // instead of scattering a (k+1)-th time; k = 1 gives single scattering alone, to check
  // against closed forms.
  int max_scattering_order = 0;
  // 0: every scattering order. k > 0: exits after fewer than k scattering events are not
  // tallied (neither radial bins, totals nor exit-cosine bins); their weight still leaves
  // the medium and is counted in MonteCarloResult::low_order_exits. k = 2 leaves out the
  // once-scattered light, for profiles whose single scattering the renderer adds apart in
  // closed form (ModelOptions::single_scattering_apart, SingleScattering.h). Must not
  // exceed max_scattering_order when that is > 0.
  int min_scattering_order = 0;
  // The beam's cosine to the normal outside the medium, in (0, 1]: photons start along its
  // refracted direction (Snell, in the x-z plane), still per unit power that entered.
  double incidence_cos = 1.0;
  // > 0: also tally what leaves through the top face by its cosine to the normal outside
  // (after refraction), in this many equal bins of [0, 1]: MonteCarloResult::
  // reflectance_by_exit_cosine (the single-scattering checks bin by exit angle).
  int exit_cosine_bins = 0;
};

// Photons per chunk: the unit of work, of RNG streams and of the ordered reduction.
inline constexpr std::uint64_t kMonteCarloChunkPhotons = 4096;

// Standard errors use the per-photon contributions x_p (a photon's summed exits into a
// bin, or through a face): SE = sqrt((Σx² - N x̄²) / (N (N - 1))), divided by the
// annulus area for binned values. With photons == 1 they are +infinity (unknown).
struct MonteCarloTally {
  std::vector<double> value;    // mean over the annulus, mm^-2: Σ weight / (N π (r1² - r0²))
  std::vector<double> stderr_;  // its standard error
  double total = 0.0;           // total flux fraction (exits at any radius)
  double total_stderr = 0.0;
};

struct MonteCarloResult {
  std::vector<double> bin_edges_mm;
  MonteCarloTally reflectance;    // exits through the top face (z = 0)
  MonteCarloTally transmittance;  // exits through the bottom face (slabs, stacks with a finite last layer)
  // With exit_cosine_bins = n: value[k] is the flux fraction leaving the top face per unit
  // of outside exit cosine μo in [k/n, (k+1)/n) (Σ weight / (N / n)), so Σ value / n =
  // reflectance.total; total and total_stderr as reflectance's.
  MonteCarloTally reflectance_by_exit_cosine;
  std::uint64_t photons = 0;
  std::uint64_t scattering_events = 0;
  // Weight absorbed in the medium (all layers) per unit power entered, with its standard error. In
  // expectation reflectance.total + transmittance.total + low_order_exits + absorbed = 1
  // when no photon was truncated and max_scattering_order == 0 (roulette is unbiased, so
  // it adds no bias); low_order_exits is 0 when min_scattering_order is 0.
  double absorbed = 0.0;
  double absorbed_stderr = 0.0;
  // Weight that left through either face after fewer than min_scattering_order scattering
  // events (not tallied anywhere else), with its standard error.
  double low_order_exits = 0.0;
  double low_order_exits_stderr = 0.0;
  std::uint64_t truncated_photons = 0;  // stopped by max_interactions_per_photon
  double seconds = 0.0;
};

// Throws std::invalid_argument whose message starts with the offending field
// ("sigma_a: ...", "photons: ...", "bin_edges_mm: ...", "thickness_mm: ...", "threads: ...",
// "roulette_weight: ...", "incidence_cos: ...", "exit_cosine_bins: ...",
// "min_scattering_order: ...", ...) for invalid coefficients (Coefficients::validate), photons
// == 0, threads < 0, a thickness that is not > 0 (NaN included), or bin edges that are
// not finite, >= 0 and strictly ascending, a negative scattering order bound, or
// min_scattering_order above a max_scattering_order > 0. An empty bin_edges_mm is allowed
// (totals only); a single edge is not (it bounds no bin).
// The one-layer case of run_layered_monte_carlo: the stack {Layer{c, opt.thickness_mm}}.
MonteCarloResult run_monte_carlo(const Coefficients& c, const MonteCarloOptions& opt);

// The walk in a stack of layers, top first (see the top of this file). opt.thickness_mm
// must stay at its default (infinity): the layers give the thicknesses. Throws
// std::invalid_argument whose message starts with the offending field: "layers: must not
// be empty"; "layers[k].sigma_a: ...", "layers[k].g: ...", ... (Coefficients::validate of
// layer k); "layers[k].thickness_mm: ..." unless every layer but the last is finite and
// > 0 and the last is > 0 (infinity allowed); "layers[k].eta: must equal layers[0].eta
// (interfaces between layers are index-matched) ..."; "thickness_mm: ..." when
// opt.thickness_mm is not infinity; and every option error of run_monte_carlo. A
// one-layer stack gives run_monte_carlo's result bit for bit.
MonteCarloResult run_layered_monte_carlo(const std::vector<Layer>& layers,
                                         const MonteCarloOptions& opt);

// Returns count + 2 edges: {0, lo, lo q, lo q², ..., hi} with q = (hi/lo)^(1/count), i.e.
// the disc [0, lo] followed by `count` log-spaced annuli from lo to hi (the last edge is
// exactly hi). Throws std::invalid_argument unless 0 < lo < hi (finite) and count >= 1.
std::vector<double> log_bin_edges(double lo, double hi, int count);

}  // namespace sss::profiles
