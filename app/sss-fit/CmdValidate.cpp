#include "CommandSupport.h"

#include "profiles/Validation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace sss::app {

namespace {

// The layered model against the layered Monte Carlo walk of the same stack, channel by
// channel, as validate_against_monte_carlo compares one medium's models: the totals, and
// R(r) as averages over vo.bins log-spaced annuli of r in [vo.r_lo_mfp, vo.r_hi_mfp], read
// here in mm (a stack has no one mean free path to scale them by).
profiles::ValidationReport validate_stack(const profiles::LayerStack& stack,
                                          const profiles::ValidationOptions& vo) {
  const auto start = std::chrono::steady_clock::now();
  const profiles::RgbProfile profile = profiles::make_layered_rgb_profile(stack, vo.model_options);
  profiles::ValidationReport report;
  report.models.push_back({profiles::Model::Layered, {}});
  for (int c = 0; c < 3; ++c) {
    profiles::MonteCarloOptions mc;
    mc.photons = vo.photons;
    mc.seed = vo.seed + 1000003ull * static_cast<std::uint64_t>(c);  // as Validation.cpp
    mc.threads = vo.threads;
    mc.bin_edges_mm = profiles::log_bin_edges(vo.r_lo_mfp, vo.r_hi_mfp, vo.bins);
    if (vo.model_options.single_scattering_apart) mc.min_scattering_order = 2;
    if (vo.progress) mc.progress = [&, c](double f) { vo.progress((c + f) / 3.0); };
    report.monte_carlo[c] = profiles::run_layered_monte_carlo(profiles::channel_layers(stack, c), mc);
    const profiles::MonteCarloResult& res = report.monte_carlo[c];

    // Annuli inside the range: log_bin_edges puts the disc [0, lo] first, skip it.
    std::vector<double> rel_se;
    double sum2 = 0.0, worst = 0.0;
    int n = 0;
    for (std::size_t b = 1; b + 1 < res.bin_edges_mm.size(); ++b) {
      const double mc_value = res.reflectance.value[b];
      if (!(mc_value > 0.0)) continue;
      rel_se.push_back(res.reflectance.stderr_[b] / mc_value);
      const double model_value = profiles::annulus_average(profile.channel(c), res.bin_edges_mm[b],
                                                           res.bin_edges_mm[b + 1]);
      const double e = model_value / mc_value - 1.0;
      sum2 += e * e;
      worst = std::max(worst, std::fabs(e));
      ++n;
    }
    std::sort(rel_se.begin(), rel_se.end());
    report.median_bin_rel_stderr[c] = rel_se.empty() ? 0.0 : rel_se[rel_se.size() / 2];

    profiles::ChannelComparison& out = report.models[0].channels[c];
    out.total = profile.channel(c).total_reflectance();
    out.total_rel_error = out.total / res.reflectance.total - 1.0;
    out.total_transmittance = profile.channel(c).total_transmittance();
    if (res.transmittance.total > 0.0)
      out.total_transmittance_rel_error = out.total_transmittance / res.transmittance.total - 1.0;
    out.rms_rel_error = n ? std::sqrt(sum2 / n) : 0.0;
    out.max_rel_error = worst;
  }
  report.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

// The walk's totals and noise, per channel, as both outputs print them.
struct WalkTotals {
  Rgb total, total_se, noise, t, t_se;
  explicit WalkTotals(const profiles::ValidationReport& rep) {
    for (int c = 0; c < 3; ++c) {
      total[c] = rep.monte_carlo[c].reflectance.total;
      total_se[c] = rep.monte_carlo[c].reflectance.total_stderr;
      t[c] = rep.monte_carlo[c].transmittance.total;
      t_se[c] = rep.monte_carlo[c].transmittance.total_stderr;
      noise[c] = rep.median_bin_rel_stderr[c];
    }
  }
};

// `--json`: the walk and every model's errors; transmittance where the walk has a far face.
nlohmann::json validation_json(const CommonArgs& a, const ProfileSource& src, const profiles::ValidationOptions& vo,
                               const profiles::ValidationReport& rep, bool far_face) {
  const bool stack = src.layers.has_value();
  const WalkTotals mc(rep);
  nlohmann::json models = nlohmann::json::array();
  for (const auto& m : rep.models) {
    Rgb tot, terr, rms, mx, t, t_err;
    for (int c = 0; c < 3; ++c) {
      tot[c] = m.channels[c].total;
      terr[c] = m.channels[c].total_rel_error;
      rms[c] = m.channels[c].rms_rel_error;
      mx[c] = m.channels[c].max_rel_error;
      t[c] = m.channels[c].total_transmittance;
      t_err[c] = m.channels[c].total_transmittance_rel_error;
    }
    nlohmann::json entry = {{"model", profiles::model_name(m.model)},
                            {"total_reflectance", to_json(tot)},
                            {"total_relative_error", to_json(terr)},
                            {"rms_relative_error", to_json(rms)},
                            {"max_relative_error", to_json(mx)}};
    if (far_face) {
      entry["total_transmittance"] = to_json(t);
      entry["total_transmittance_relative_error"] = to_json(t_err);
    }
    models.push_back(std::move(entry));
  }
  nlohmann::json out = {
      {"medium", src.description},
      {stack ? "range_mm" : "range_mfp", {vo.r_lo_mfp, vo.r_hi_mfp}},
      {"monte_carlo",
       {{"photons", a.photons},
        {"seed", a.seed},
        {"seconds", rep.seconds},
        {"total_reflectance", to_json(mc.total)},
        {"total_reflectance_stderr", to_json(mc.total_se)},
        {"median_bin_relative_stderr", to_json(mc.noise)}}},
      {"models", models}};
  if (far_face) {
    out["monte_carlo"]["total_transmittance"] = to_json(mc.t);
    out["monte_carlo"]["total_transmittance_stderr"] = to_json(mc.t_se);
  }
  if (stack) out["layers"] = layers_json(*src.layers);
  return out;
}

// The text report: the walk, then a row per model and channel, then the transmittances.
void print_validation(const CommonArgs& a, const ProfileSource& src, const profiles::ValidationOptions& vo,
                      const profiles::ValidationReport& rep, bool far_face) {
  const bool stack = src.layers.has_value();
  const WalkTotals mc(rep);
  std::printf("%s against Monte Carlo for %s\n", stack ? "Model layered" : "Models",
              src.description.c_str());
  std::printf("Monte Carlo: %llu photons per channel, seed %llu, %.1f s\n",
              static_cast<unsigned long long>(a.photons), static_cast<unsigned long long>(a.seed),
              rep.seconds);
  std::printf("MC total reflectance   %.5f±%.5f  %.5f±%.5f  %.5f±%.5f\n", mc.total[0], mc.total_se[0],
              mc.total[1], mc.total_se[1], mc.total[2], mc.total_se[2]);
  if (far_face)
    std::printf("MC total transmittance %.5f±%.5f  %.5f±%.5f  %.5f±%.5f\n", mc.t[0], mc.t_se[0],
                mc.t[1], mc.t_se[1], mc.t[2], mc.t_se[2]);
  std::printf("R(r) compared on %d annuli over r = %.2g..%.2g %s "
              "(MC noise per annulus: %.2f%% %.2f%% %.2f%%)\n\n",
              vo.bins, vo.r_lo_mfp, vo.r_hi_mfp, stack ? "mm" : "reduced mean free paths",
              100 * mc.noise[0], 100 * mc.noise[1], 100 * mc.noise[2]);
  std::printf("%-14s %-3s %9s %10s %10s %10s\n", "model", "ch", "total", "total err", "RMS err",
              "max err");
  for (const auto& m : rep.models) {
    for (int c = 0; c < 3; ++c) {
      const auto& ch = m.channels[c];
      std::printf("%-14s %-3s %9.5f %+9.2f%% %9.1f%% %9.1f%%\n",
                  c == 0 ? std::string(profiles::model_name(m.model)).c_str() : "",
                  kChannelNames[c], ch.total, 100 * ch.total_rel_error, 100 * ch.rms_rel_error,
                  100 * ch.max_rel_error);
    }
  }
  if (far_face) {
    std::printf("\n%-14s %-3s %9s %10s\n", "model", "ch", "T total", "T err");
    for (const auto& m : rep.models)
      for (int c = 0; c < 3; ++c)
        std::printf("%-14s %-3s %9.5f %+9.2f%%\n",
                    c == 0 ? std::string(profiles::model_name(m.model)).c_str() : "",
                    kChannelNames[c], m.channels[c].total_transmittance,
                    100 * m.channels[c].total_transmittance_rel_error);
  }
}

}  // namespace

int run_validate(const CommonArgs& a) {
  const auto opt = model_options(a);
  const auto src = resolve_source(a, opt, /*with_model=*/false);
  if (!src) return kExitUsage;

  profiles::ValidationOptions vo;
  vo.photons = a.photons;
  vo.seed = a.seed;
  vo.threads = a.threads;
  vo.model_options = opt;
  vo.progress = [](double f) { progress_bar("Monte Carlo", f); };
  const bool stack = src->layers.has_value();
  const auto rep = stack ? validate_stack(*src->layers, vo)
                         : profiles::validate_against_monte_carlo(src->medium, vo);
  // The walk has a far face: a slab, or a stack whose last layer is finite.
  const bool far_face = stack ? src->has_transmittance() : src->medium.is_slab();
  if (a.json)
    std::cout << validation_json(a, *src, vo, rep, far_face).dump(2) << '\n';
  else
    print_validation(a, *src, vo, rep, far_face);
  return kExitOk;
}

}  // namespace sss::app
