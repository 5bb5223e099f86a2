#include "CommandSupport.h"

#include "profiles/Presets.h"

#include <cstdio>
#include <iostream>

namespace sss::app {

int run_presets(bool json) {
  if (json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& p : profiles::presets()) {
      const bool usable = !profiles::preset_medium(p).validate();
      out.push_back({{"name", p.name},
                     {"sigma_s_reduced", to_json(p.sigma_s_reduced)},
                     {"sigma_a", to_json(p.sigma_a)},
                     {"eta", p.eta},
                     {"published_reflectance", to_json(p.published_reflectance)},
                     {"usable", usable}});
    }
    std::cout << out.dump(2) << '\n';
    return kExitOk;
  }
  std::printf("Measured media, Jensen et al. 2001 (g = 0, so sigma_s = sigma_s'); mm^-1\n");
  std::printf("%-11s %-22s %-25s %-5s %s\n", "name", "sigma_s' R,G,B", "sigma_a R,G,B", "eta",
              "published Rd");
  for (const auto& p : profiles::presets()) {
    char ss[64], sa[64], rd[64];
    std::snprintf(ss, sizeof ss, "%.2f,%.2f,%.2f", p.sigma_s_reduced[0], p.sigma_s_reduced[1],
                  p.sigma_s_reduced[2]);
    std::snprintf(sa, sizeof sa, "%.4g,%.4g,%.4g", p.sigma_a[0], p.sigma_a[1], p.sigma_a[2]);
    std::snprintf(rd, sizeof rd, "%.2f,%.2f,%.2f", p.published_reflectance[0],
                  p.published_reflectance[1], p.published_reflectance[2]);
    const bool usable = !profiles::preset_medium(p).validate();
    std::printf("%-11s %-22s %-25s %-5.2g %s%s\n", std::string(p.name).c_str(), ss, sa, p.eta, rd,
                usable ? "" : "  (sigma_a = 0: albedo 1, not usable by the models)");
  }
  return kExitOk;
}

}  // namespace sss::app
