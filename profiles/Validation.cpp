#include "profiles/Validation.h"

#include "profiles/Integrate.h"
#include "profiles/McTable.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace sss::profiles {

namespace {

// Whether every channel's η lies on the shipped mc-table's axis (it covers the library's
// whole range, [1, 2.5], and extrapolates in albedo past its last node): outside it
// mc-table refuses the medium, and the default list leaves it out rather than fail the
// whole comparison (asking for it by name still gives that error).
bool inside_mc_table(const Medium& m) {
  const McTableData& t = shipped_mc_table();
  for (int c = 0; c < 3; ++c) {
    const Coefficients k = m.channel(c);
    if (!(k.eta >= t.eta.front() && k.eta <= t.eta.back())) return false;
  }
  return true;
}

}  // namespace

std::vector<Model> default_validation_models(const Medium& m) {
  std::vector<Model> models = {Model::Dipole, Model::BetterDipole, Model::Pbd, Model::Qd, Model::Burley};
  // mc-table is semi-infinite like the four above (on a slab they are all compared with
  // the slab's Monte Carlo, which is what a user choosing them for a slab gets).
  if (inside_mc_table(m)) models.push_back(Model::McTable);
  if (m.is_slab()) models.push_back(Model::Multipole);
  return models;
}

double annulus_average(const RadialProfile& p, double r0, double r1, bool transmittance) {
  const double flux = integrate(
      [&](double r) {
        return 2.0 * std::numbers::pi * r * (transmittance ? p.transmittance(r) : p.reflectance(r));
      },
      r0, r1, 2, 16);
  return flux / (std::numbers::pi * (r1 * r1 - r0 * r0));
}

namespace {

// The median relative standard error of the walk's annuli inside the range (log_bin_edges
// puts the disc [0, lo] first: it is skipped).
double median_annulus_rel_stderr(const MonteCarloResult& res) {
  std::vector<double> rel_se;
  for (std::size_t b = 1; b + 1 < res.bin_edges_mm.size(); ++b)
    if (res.reflectance.value[b] > 0.0) rel_se.push_back(res.reflectance.stderr_[b] / res.reflectance.value[b]);
  std::sort(rel_se.begin(), rel_se.end());
  return rel_se.empty() ? 0.0 : rel_se[rel_se.size() / 2];
}

// One model's channel against the walk: totals, and R(r)'s relative error over the annuli
// (RMS and worst) where the walk has reflectance.
ChannelComparison compare_channel(const RadialProfile& profile, const MonteCarloResult& res) {
  ChannelComparison out;
  out.total = profile.total_reflectance();
  out.total_transmittance = profile.total_transmittance();
  out.total_rel_error = out.total / res.reflectance.total - 1.0;
  if (res.transmittance.total > 0.0)
    out.total_transmittance_rel_error = out.total_transmittance / res.transmittance.total - 1.0;
  double sum2 = 0.0, worst = 0.0;
  int n = 0;
  for (std::size_t b = 1; b + 1 < res.bin_edges_mm.size(); ++b) {
    const double mc_value = res.reflectance.value[b];
    if (!(mc_value > 0.0)) continue;
    const double model_value = annulus_average(profile, res.bin_edges_mm[b], res.bin_edges_mm[b + 1]);
    const double e = model_value / mc_value - 1.0;
    sum2 += e * e;
    worst = std::max(worst, std::fabs(e));
    ++n;
  }
  out.rms_rel_error = n ? std::sqrt(sum2 / n) : 0.0;
  out.max_rel_error = worst;
  return out;
}

}  // namespace

ValidationReport validate_against_monte_carlo(const Medium& medium,
                                              const ValidationOptions& opt) {
  if (auto e = medium.validate()) throw std::invalid_argument(e->what());
  if (!(opt.r_lo_mfp > 0.0) || !(opt.r_hi_mfp > opt.r_lo_mfp) || opt.bins < 1)
    throw std::invalid_argument("validation range: need 0 < r_lo < r_hi and bins >= 1");
  const auto start = std::chrono::steady_clock::now();
  ValidationReport report;
  const std::vector<Model> models =
      opt.models.empty() ? default_validation_models(medium) : opt.models;
  report.models.resize(models.size());
  for (std::size_t i = 0; i < models.size(); ++i) report.models[i].model = models[i];

  for (int c = 0; c < 3; ++c) {
    if (!opt.channels[c]) continue;
    const Coefficients k = medium.channel(c);
    const double mfp = k.mfp_reduced();
    MonteCarloOptions mc;
    mc.photons = opt.photons;
    mc.seed = opt.seed + 1000003ull * static_cast<std::uint64_t>(c);
    mc.threads = opt.threads;
    mc.thickness_mm = medium.thickness_mm;
    mc.bin_edges_mm = log_bin_edges(opt.r_lo_mfp * mfp, opt.r_hi_mfp * mfp, opt.bins);
    // Models without single scattering are compared with the walk's exits after two or
    // more scattering events, as model mc itself leaves them out.
    if (opt.model_options.single_scattering_apart) mc.min_scattering_order = 2;
    if (opt.progress)
      mc.progress = [&, c](double f) { opt.progress((c + f) / 3.0); };
    report.monte_carlo[c] = run_monte_carlo(k, mc);
    report.median_bin_rel_stderr[c] = median_annulus_rel_stderr(report.monte_carlo[c]);
    for (ModelComparison& mcmp : report.models)
      mcmp.channels[c] = compare_channel(*make_profile(mcmp.model, k, medium.thickness_mm, opt.model_options),
                                         report.monte_carlo[c]);
  }
  report.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace sss::profiles
