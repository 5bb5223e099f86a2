#include "CommandSupport.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <vector>

namespace sss::app {

namespace {

std::variant<std::vector<double>, FieldError> parse_radii(const std::string& text, bool log) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ':');) parts.push_back(item);
  const FieldError shape{"--radii", "expected START:STOP:COUNT, got '" + text + "'"};
  if (parts.size() != 3) return shape;
  auto a = parse_number("--radii", parts[0]);
  auto b = parse_number("--radii", parts[1]);
  auto n = parse_number("--radii", parts[2]);
  if (std::holds_alternative<FieldError>(a) || std::holds_alternative<FieldError>(b) ||
      std::holds_alternative<FieldError>(n))
    return shape;
  const double start = std::get<double>(a), stop = std::get<double>(b), count = std::get<double>(n);
  if (!std::isfinite(start) || !std::isfinite(stop) || start < 0.0 || stop < start)
    return FieldError{"--radii", "need 0 <= START <= STOP (mm), got '" + text + "'"};
  if (!(count >= 1.0) || count > 1e6 || count != std::floor(count))
    return FieldError{"--radii", "COUNT must be an integer in [1, 1000000], got '" + parts[2] + "'"};
  if (log && !(start > 0.0))
    return FieldError{"--radii", "--log needs START > 0"};
  const int m = static_cast<int>(count);
  std::vector<double> r(m);
  for (int i = 0; i < m; ++i) {
    const double t = m == 1 ? 0.0 : static_cast<double>(i) / (m - 1);
    r[i] = log ? start * std::pow(stop / start, t) : start + (stop - start) * t;
  }
  return r;
}

}  // namespace

int run_profile(const ProfileArgs& a) {
  const auto opt = model_options(a.common);
  const auto src = resolve_source(a.common, opt, /*with_model=*/true);
  if (!src) return kExitUsage;
  auto radii = parse_radii(a.radii, a.log_spacing);
  if (auto* e = std::get_if<FieldError>(&radii)) return usage_error(*e);
  if (!src->layers && src->medium.is_slab() && src->model != profiles::Model::Multipole &&
      src->model != profiles::Model::MonteCarlo)
    std::cerr << "sss-fit: note: model " << src->model_name
              << " describes a semi-infinite medium and ignores --thickness\n";

  const profiles::RgbProfile profile = src->make_profile(opt);
  const auto& r = std::get<std::vector<double>>(radii);
  const bool slab = src->has_transmittance();

  if (a.common.json) {
    nlohmann::json R = nlohmann::json::array(), T = nlohmann::json::array();
    for (double x : r) {
      R.push_back(to_json(profile.reflectance(x)));
      if (slab) T.push_back(to_json(profile.transmittance(x)));
    }
    nlohmann::json out = {{"model", src->model_name},
                          {"medium", src->description},
                          {"radii_mm", r},
                          {"R", R},
                          {"total_reflectance", to_json(profile.total_reflectance())}};
    if (src->layers) out["layers"] = layers_json(*src->layers);
    if (slab) {
      out["T"] = T;
      out["total_transmittance"] = to_json(profile.total_transmittance());
    }
    std::cout << out.dump() << '\n';
    return kExitOk;
  }
  const auto tot = profile.total_reflectance();
  std::printf("# model %s, %s\n# total reflectance R,G,B = %.6f %.6f %.6f\n",
              src->model_name.c_str(), src->description.c_str(), tot[0], tot[1], tot[2]);
  std::printf("# r_mm  R_r R_g R_b (mm^-2)%s\n", slab ? "  T_r T_g T_b (mm^-2)" : "");
  for (double x : r) {
    const auto v = profile.reflectance(x);
    std::printf("%.6g %.6e %.6e %.6e", x, v[0], v[1], v[2]);
    if (slab) {
      const auto t = profile.transmittance(x);
      std::printf(" %.6e %.6e %.6e", t[0], t[1], t[2]);
    }
    std::printf("\n");
  }
  return kExitOk;
}

}  // namespace sss::app
