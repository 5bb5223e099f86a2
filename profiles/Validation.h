// Every model against the Monte Carlo reference for one medium: the error of the total
// reflectance, and the RMS and max relative error of R(r) over r ∈ [0.25, 8] reduced mean
// free paths, compared as averages over the same annuli (so binning adds no bias).
// This backs `sss-fit validate` and the model-vs-MC tests.
#pragma once

#include "profiles/Medium.h"
#include "profiles/MonteCarlo.h"
#include "profiles/Profile.h"

#include <array>
#include <functional>
#include <vector>

namespace sss::profiles {

struct ValidationOptions {
  std::uint64_t photons = 1u << 20;  // per channel
  std::uint64_t seed = 1;
  int threads = 0;
  double r_lo_mfp = 0.25;  // comparison range, in reduced mean free paths 1/σt'
  double r_hi_mfp = 8.0;
  int bins = 24;           // log-spaced annuli over the range
  std::vector<Model> models;  // empty: every analytic model that applies to the medium
  // With single_scattering_apart the Monte Carlo reference leaves the once-scattered
  // exits out too (MonteCarloOptions::min_scattering_order = 2).
  ModelOptions model_options;
  std::function<void(double)> progress;  // fraction of the Monte Carlo done
  std::array<bool, 3> channels{true, true, true};  // which channels to run (tests use one)
};

struct ChannelComparison {
  double total = 0.0;            // the model's total reflectance
  double total_rel_error = 0.0;  // (model - MC) / MC
  double rms_rel_error = 0.0;    // over the annuli in range
  double max_rel_error = 0.0;    // largest |model - MC| / MC over the annuli
  double total_transmittance = 0.0;  // slabs only
  double total_transmittance_rel_error = 0.0;  // (model - MC) / MC, slabs only
};

struct ModelComparison {
  Model model;
  std::array<ChannelComparison, 3> channels;
};

struct ValidationReport {
  std::array<MonteCarloResult, 3> monte_carlo;  // one run per channel
  std::array<double, 3> median_bin_rel_stderr{};  // MC noise on the compared annuli
  std::vector<ModelComparison> models;
  double seconds = 0.0;
};

// The models compared by default: all analytic ones; the multipole only for slabs.
std::vector<Model> default_validation_models(const Medium& m);

// Throws std::invalid_argument for an invalid medium or options.
ValidationReport validate_against_monte_carlo(const Medium& medium,
                                              const ValidationOptions& opt);

// The mean of R over the annulus [r0, r1]: ∫ 2πr R dr / π(r1² - r0²).
double annulus_average(const RadialProfile& p, double r0, double r1, bool transmittance = false);

}  // namespace sss::profiles
