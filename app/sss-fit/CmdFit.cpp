#include "CliSupport.h"
#include "CommandSupport.h"
#include "SvgPlot.h"

#include "profiles/EdgeResponse.h"
#include "profiles/GaussianFit.h"
#include "profiles/KernelExport.h"
#include "profiles/MonteCarlo.h"

#include <algorithm>
#include <chrono>
#include <initializer_list>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>

namespace sss::app {

namespace {

constexpr const char* kChannelColor[3] = {"#d62728", "#2ca02c", "#1f77b4"};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool ends_with_any(const std::string& path, std::initializer_list<const char*> extensions) {
  const std::string ext = lower_extension(path);
  for (const char* e : extensions)
    if (ext == e) return true;
  return false;
}

// Wrong units make kernels no renderer can use: σ typed in m^-1 (1000 times too dense)
// gives Gaussians of nanometres (skin1 in m^-1: the narrowest 81 nm wide), an mfp typed in
// metres the same. In mm^-1 the narrowest Gaussian of every preset's fit is 23 µm (cream)
// to 230 µm wide (standard deviation, mc-table), and a 10 µm mfp gives 1.5 µm: a narrowest
// Gaussian under 1 µm, or a widest over a metre, is said.
void warn_kernel_size(const profiles::GaussianFit& fit) {
  if (fit.variances_mm2.empty()) return;
  const auto [lo, hi] = std::minmax_element(fit.variances_mm2.begin(), fit.variances_mm2.end());
  const double widest = std::sqrt(*hi), narrowest = std::sqrt(*lo);
  if (narrowest < 1e-3)
    std::cerr << "sss-fit: warning: the narrowest Gaussian is " << message_number(1e3 * narrowest)
              << " µm wide (standard deviation), under 1 µm: are σ given in mm^-1 and the mfp "
                 "in mm? (values in m^-1 are 1000 times too large)\n";
  if (widest > 1e3)
    std::cerr << "sss-fit: warning: the widest Gaussian is " << message_number(1e-3 * widest)
              << " m wide (standard deviation), over a metre: are σ given in mm^-1 and the "
                 "mfp in mm?\n";
}

// The error a renderer sees across a straight light edge: max over x of
// |M(x) - M_fit(x)| / total, per channel (M is the edge response, EdgeResponse.h).
Rgb edge_error(const profiles::RgbProfile& profile, const profiles::GaussianFit& fit) {
  Rgb worst{};
  const double lo = 0.01 * profile.inner_radius(), hi = profile.support_radius();
  for (int i = 0; i <= 48; ++i) {
    const double x = lo * std::pow(hi / lo, i / 48.0);
    const Rgb exact = profiles::edge_response(profile, x);
    const Rgb fitted = profiles::edge_response(fit, x);
    for (int c = 0; c < 3; ++c)
      worst[c] = std::max(worst[c], std::fabs(exact[c] - fitted[c]) / fit.total_reflectance[c]);
  }
  return worst;
}

// Channel c's Monte Carlo of the same medium (sss-fit fit --plot-mc), r·R with error bars.
PlotSeries monte_carlo_series(const ProfileSource& src, int c, const profiles::ModelOptions& opt) {
  // From 0.02 of the shortest reduced mean free path to 20 of the longest diffusion
  // lengths 1/σtr among the layers (the medium's own for one medium).
  double mfp = std::numeric_limits<double>::infinity(), diffusion = 0.0;
  for (const profiles::Coefficients& k : src.channel_media(c)) {
    mfp = std::min(mfp, k.mfp_reduced());
    diffusion = std::max(diffusion, 1.0 / k.sigma_tr_classical());
  }
  profiles::MonteCarloOptions mc;
  mc.photons = opt.mc_photons;
  mc.seed = opt.mc_seed + c;
  mc.threads = opt.mc_threads;
  mc.bin_edges_mm = profiles::log_bin_edges(0.02 * mfp, 20.0 * diffusion, 40);
  mc.progress = [c](double f) { progress_bar("Monte Carlo", (c + f) / 3.0); };
  const auto res = src.monte_carlo(c, mc);
  PlotSeries pts;
  pts.label = std::string(kChannelNames[c]) + " Monte Carlo";
  pts.color = kChannelColor[c];
  pts.markers = true;
  for (std::size_t b = 1; b + 1 < res.bin_edges_mm.size(); ++b) {
    const double r0 = res.bin_edges_mm[b], r1 = res.bin_edges_mm[b + 1];
    const double r = std::sqrt(0.5 * (r0 * r0 + r1 * r1));
    pts.x.push_back(r);
    pts.y.push_back(r * res.reflectance.value[b]);
    pts.y_err.push_back(r * res.reflectance.stderr_[b]);
  }
  return pts;
}

// The numbers under the legend: the fit's errors and total reflectance.
std::vector<std::string> plot_notes(const profiles::GaussianFit& fit, const Rgb& edge) {
  std::vector<std::string> notes;
  char line[128];
  std::snprintf(line, sizeof line, "relative L2 error of r·R:");
  notes.push_back(line);
  std::snprintf(line, sizeof line, "R %.2f%%  G %.2f%%  B %.2f%%", 100 * fit.relative_error[0],
                100 * fit.relative_error[1], 100 * fit.relative_error[2]);
  notes.push_back(line);
  notes.push_back("max edge-response error:");
  std::snprintf(line, sizeof line, "R %.2f%%  G %.2f%%  B %.2f%%", 100 * edge[0], 100 * edge[1],
                100 * edge[2]);
  notes.push_back(line);
  std::snprintf(line, sizeof line, "total reflectance:");
  notes.push_back(line);
  std::snprintf(line, sizeof line, "%.4f %.4f %.4f", fit.total_reflectance[0],
                fit.total_reflectance[1], fit.total_reflectance[2]);
  notes.push_back(line);
  if (fit.prefilter_variance_mm2 > 0.0) {
    std::snprintf(line, sizeof line, "errors at resolution %.3g mm:",
                  std::sqrt(fit.prefilter_variance_mm2));
    notes.push_back(line);
    notes.push_back("both blurred by a Gaussian of");
    notes.push_back("that standard deviation");
  }
  notes.push_back("solid: model, dashed: fit");
  return notes;
}

LogLogPlot make_plot(const FitArgs& a, const ProfileSource& src, const profiles::RgbProfile& profile,
                     const profiles::FitTarget& target, const profiles::GaussianFit& fit,
                     const Rgb& edge, const profiles::ModelOptions& opt) {
  LogLogPlot plot;
  plot.title = "r·R(r): " + src.model_name + " and a " + std::to_string(a.gaussians) +
               "-Gaussian fit — " + src.description;
  plot.x_label = "r (mm)";
  plot.y_label = "r·R(r) (mm^-1)";
  for (int c = 0; c < 3; ++c) {
    PlotSeries model;
    model.label = std::string(kChannelNames[c]) + " " + src.model_name;
    model.color = kChannelColor[c];
    PlotSeries fitted;
    fitted.label = std::string(kChannelNames[c]) + " fit";
    fitted.color = kChannelColor[c];
    fitted.dashed = true;
    for (std::size_t i = 0; i < target.r_mm.size(); ++i) {
      const double r = target.r_mm[i];
      // The fit samples from 1e-3 of the innermost length; the plot starts at 1e-2 of it,
      // where r·R is still rising, and so spends no decades on nothing.
      if (r < 10.0 * target.r_mm.front()) continue;
      model.x.push_back(r);
      // The profile itself (the target's samples are blurred when the fit has a
      // resolution): the plot shows what the kernel leaves out below it.
      model.y.push_back(r * profile.reflectance(r)[c]);
      fitted.x.push_back(r);
      fitted.y.push_back(r * fit.evaluate(r)[c]);
    }
    plot.series.push_back(std::move(model));
    plot.series.push_back(std::move(fitted));
  }
  if (a.plot_mc)
    for (int c = 0; c < 3; ++c) plot.series.push_back(monte_carlo_series(src, c, opt));
  plot.notes = plot_notes(fit, edge);
  return plot;
}

// The fit as text: its Gaussians, totals and errors, the times, the separable taps.
void print_fit(const FitArgs& a, const ProfileSource& src, const profiles::GaussianFit& fit,
               const Rgb& edge, const profiles::SeparableKernel* separable, double ms_profile,
               double ms_fit) {
  std::printf("%d-Gaussian fit of %s for %s\n", a.gaussians, src.model_name.c_str(),
              src.description.c_str());
  std::printf("G(v,r) = exp(-r^2/2v)/(2 pi v);  R(r) ~ sum_i w_i G(v_i, r)\n\n");
  std::printf("  %-12s %-12s %-12s %-12s\n", "v (mm^2)", "w_R", "w_G", "w_B");
  for (std::size_t i = 0; i < fit.variances_mm2.size(); ++i)
    std::printf("  %-12.5g %-12.5g %-12.5g %-12.5g\n", fit.variances_mm2[i], fit.weights[i][0],
                fit.weights[i][1], fit.weights[i][2]);
  std::printf("\ntotal reflectance     %.6f %.6f %.6f\n", fit.total_reflectance[0],
              fit.total_reflectance[1], fit.total_reflectance[2]);
  std::printf("relative L2 error    %.3f%% %.3f%% %.3f%%   (of r*R(r), measure dr)\n",
              100 * fit.relative_error[0], 100 * fit.relative_error[1],
              100 * fit.relative_error[2]);
  std::printf("edge-response error  %.3f%% %.3f%% %.3f%%   (max |M - M_fit| / total across a light edge)\n",
              100 * edge[0], 100 * edge[1], 100 * edge[2]);
  if (fit.prefilter_variance_mm2 > 0.0)
    std::printf("resolution           %.4g mm   (the L2 error compares model and fit both blurred by a\n"
                "                     Gaussian of this standard deviation; --resolution 0: unblurred)\n",
                std::sqrt(fit.prefilter_variance_mm2));
  std::printf("time: profile %.2f ms, sampling + fit %.2f ms\n", ms_profile, ms_fit);
  if (separable) {
    std::printf("\nseparable kernel, %d taps over +-%.4g mm (weights sum to 1 per channel):\n",
                a.taps, separable->range_mm);
    for (std::size_t i = 0; i < separable->offsets_mm.size(); ++i)
      std::printf("  %+10.5f mm  %.6f %.6f %.6f\n", separable->offsets_mm[i],
                  separable->weights[i][0], separable->weights[i][1], separable->weights[i][2]);
  }
}

// The options that need no medium; the exit code of a refusal.
std::optional<int> check_fit_args(const FitArgs& a) {
  if (!profiles::valid_gaussian_count(a.gaussians))
    return usage_error("--gaussians: " + profiles::gaussian_count_rule() + ", got " + std::to_string(a.gaussians));
  if (a.taps != 0 && (a.taps < 3 || a.taps % 2 == 0 || a.taps > 255))
    return usage_error("--taps: must be odd and in [3, 255], got " + std::to_string(a.taps));
  // The file names say the format: an SVG named .png would not open as one.
  if (!a.out.empty() && !ends_with_any(a.out, {".json", ".h", ".hpp"}))
    return usage_error("--out: writes a JSON kernel (.json) or a C header (.h, .hpp), got '" + a.out + "'");
  if (!a.plot.empty() && !ends_with_any(a.plot, {".svg"}))
    return usage_error("--plot: writes an SVG plot, name it .svg, got '" + a.plot + "'");
  return std::nullopt;
}

}  // namespace

int run_fit(const FitArgs& a) {
  if (const auto refused = check_fit_args(a)) return *refused;
  const auto opt = model_options(a.common);
  const auto src = resolve_source(a.common, opt, /*with_model=*/true);
  if (!src) return kExitUsage;

  const auto t0 = std::chrono::steady_clock::now();
  const profiles::RgbProfile profile = src->make_profile(opt);
  const auto t1 = std::chrono::steady_clock::now();
  if (!(a.resolution < 0.0) && !(a.resolution <= 10.0))
    return usage_error("--resolution: must lie in [0, 10] inner radii (reduced mean free paths for mc-table and the dipoles), got " +
                       message_number(a.resolution));
  const auto target = profiles::make_fit_target(profile, a.samples, a.resolution);
  const auto fit = profiles::fit_gaussians(target, {a.gaussians});
  const auto t2 = std::chrono::steady_clock::now();

  warn_kernel_size(fit);
  const Rgb edge = edge_error(profile, fit);
  std::optional<profiles::SeparableKernel> separable;
  if (a.taps > 0) separable = profiles::make_separable_kernel(profile, a.taps);
  const profiles::KernelInfo info{src->model_name, src->description};
  const std::string json = profiles::kernel_to_json(fit, info, separable ? &*separable : nullptr);

  if (!a.out.empty()) {
    const std::string bytes =
        ends_with(a.out, ".h") || ends_with(a.out, ".hpp")
            ? profiles::kernel_to_c_header(fit, info, separable ? &*separable : nullptr,
                                           a.header_prefix)
            : json;
    if (!write_output(a.out, bytes)) return kExitRuntime;
  }
  if (!a.plot.empty() &&
      !write_output(a.plot, render_svg(make_plot(a, *src, profile, target, fit, edge, opt))))
    return kExitRuntime;

  if (a.common.json) {
    std::cout << json << '\n';
    return kExitOk;
  }
  print_fit(a, *src, fit, edge, separable ? &*separable : nullptr,
            std::chrono::duration<double, std::milli>(t1 - t0).count(),
            std::chrono::duration<double, std::milli>(t2 - t1).count());
  if (!a.out.empty()) std::printf("wrote %s\n", a.out.c_str());
  if (!a.plot.empty()) std::printf("wrote %s\n", a.plot.c_str());
  return kExitOk;
}

}  // namespace sss::app
