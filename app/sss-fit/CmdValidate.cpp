#include "CommandSupport.h"

#include "profiles/Validation.h"

#include <cstdio>
#include <iostream>

namespace sss::app {

int run_validate(const CommonArgs& a) {
  const auto opt = model_options(a);
  auto resolved = resolve_medium(a.medium, profiles::kDefaultModel, opt);
  if (auto* e = std::get_if<FieldError>(&resolved)) return usage_error(*e);
  const auto& rm = std::get<ResolvedMedium>(resolved);

  profiles::ValidationOptions vo;
  vo.photons = a.photons;
  vo.seed = a.seed;
  vo.threads = a.threads;
  vo.model_options = opt;
  vo.progress = [](double f) { progress_bar("Monte Carlo", f); };
  const auto rep = profiles::validate_against_monte_carlo(rm.medium, vo);

  Rgb mc_total, mc_se, noise;
  for (int c = 0; c < 3; ++c) {
    mc_total[c] = rep.monte_carlo[c].reflectance.total;
    mc_se[c] = rep.monte_carlo[c].reflectance.total_stderr;
    noise[c] = rep.median_bin_rel_stderr[c];
  }
  if (a.json) {
    nlohmann::json models = nlohmann::json::array();
    for (const auto& m : rep.models) {
      Rgb tot, terr, rms, mx;
      for (int c = 0; c < 3; ++c) {
        tot[c] = m.channels[c].total;
        terr[c] = m.channels[c].total_rel_error;
        rms[c] = m.channels[c].rms_rel_error;
        mx[c] = m.channels[c].max_rel_error;
      }
      models.push_back({{"model", profiles::model_name(m.model)},
                        {"total_reflectance", to_json(tot)},
                        {"total_relative_error", to_json(terr)},
                        {"rms_relative_error", to_json(rms)},
                        {"max_relative_error", to_json(mx)}});
    }
    nlohmann::json out = {
        {"medium", rm.description},
        {"range_mfp", {vo.r_lo_mfp, vo.r_hi_mfp}},
        {"monte_carlo",
         {{"photons", a.photons},
          {"seed", a.seed},
          {"seconds", rep.seconds},
          {"total_reflectance", to_json(mc_total)},
          {"total_reflectance_stderr", to_json(mc_se)},
          {"median_bin_relative_stderr", to_json(noise)}}},
        {"models", models}};
    std::cout << out.dump(2) << '\n';
    return kExitOk;
  }
  std::printf("Models against Monte Carlo for %s\n", rm.description.c_str());
  std::printf("Monte Carlo: %llu photons per channel, seed %llu, %.1f s\n",
              static_cast<unsigned long long>(a.photons), static_cast<unsigned long long>(a.seed),
              rep.seconds);
  std::printf("MC total reflectance   %.5f±%.5f  %.5f±%.5f  %.5f±%.5f\n", mc_total[0], mc_se[0],
              mc_total[1], mc_se[1], mc_total[2], mc_se[2]);
  std::printf("R(r) compared on %d annuli over r = %.2g..%.2g reduced mean free paths "
              "(MC noise per annulus: %.2f%% %.2f%% %.2f%%)\n\n",
              vo.bins, vo.r_lo_mfp, vo.r_hi_mfp, 100 * noise[0], 100 * noise[1], 100 * noise[2]);
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
  return kExitOk;
}

}  // namespace sss::app
