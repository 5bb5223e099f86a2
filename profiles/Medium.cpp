#include "profiles/Medium.h"

#include <cmath>
#include <sstream>

namespace sss {

std::string message_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace sss

namespace sss::profiles {

namespace {
const auto number = message_number;
}  // namespace

double Coefficients::sigma_tr_classical() const {
  return std::sqrt(3.0 * sigma_a * sigma_t_reduced());
}

std::optional<FieldError> Coefficients::validate(const std::string& suffix) const {
  auto bad = [&](const char* field, const std::string& why) {
    return FieldError{std::string(field) + suffix, why};
  };
  if (!std::isfinite(sigma_a)) return bad("sigma_a", "must be a finite number, got " + number(sigma_a));
  if (!std::isfinite(sigma_s)) return bad("sigma_s", "must be a finite number, got " + number(sigma_s));
  if (!std::isfinite(g)) return bad("g", "must be a finite number, got " + number(g));
  if (!std::isfinite(eta)) return bad("eta", "must be a finite number, got " + number(eta));
  if (sigma_a < 0.0) return bad("sigma_a", "must be >= 0 mm^-1, got " + number(sigma_a));
  if (sigma_s < 0.0) return bad("sigma_s", "must be >= 0 mm^-1, got " + number(sigma_s));
  if (sigma_a + sigma_s <= 0.0)
    return bad("sigma_t", "sigma_a + sigma_s must be > 0 (the medium would be empty)");
  if (sigma_a == 0.0)
    return bad("sigma_a",
               "is 0, an albedo of 1: light never dies out and the profile has no finite "
               "width; give a small positive absorption (e.g. 1e-4 mm^-1)");
  if (sigma_a > kMaxCoefficient)
    return bad("sigma_a", "must be <= " + number(kMaxCoefficient) + " mm^-1 (a mean free path "
               "of 1 nm), got " + number(sigma_a));
  if (sigma_s > kMaxCoefficient)
    return bad("sigma_s", "must be <= " + number(kMaxCoefficient) + " mm^-1 (a mean free path "
               "of 1 nm), got " + number(sigma_s));
  if (!(std::fabs(g) < 1.0)) return bad("g", "must lie in (-1, 1), got " + number(g));
  if (!(eta > 0.0)) return bad("eta", "must be > 0, got " + number(eta));
  if (eta < kEtaMin || eta > kEtaMax)
    return bad("eta", "must lie in [" + number(kEtaMin) + ", " + number(kEtaMax) +
                          "] (the index relative to the outside that the models' Fresnel "
                          "fits cover), got " + number(eta));
  if (sigma_s_reduced() < 0.0) return bad("g", "gives a negative reduced scattering");
  if (sigma_t_reduced() < kMinSigmaTReduced)
    return bad("sigma_t",
               "the reduced extinction sigma_a + sigma_s (1 - g) = " + number(sigma_t_reduced()) +
                   " mm^-1 is below " + number(kMinSigmaTReduced) +
                   " mm^-1 (a reduced mean free path over 1 km)");
  if (sigma_a < kMinAbsorptionRatio * sigma_t_reduced())
    return bad("sigma_a",
               "is " + number(sigma_a) + ", under " + number(kMinAbsorptionRatio) +
                   " of sigma_t' = " + number(sigma_t_reduced()) +
                   ": an albedo this close to 1 gives a profile over 5e5 mean free paths wide");
  return std::nullopt;
}

std::optional<FieldError> Medium::validate() const {
  for (int c = 0; c < 3; ++c) {
    if (auto e = channel(c).validate(std::string("[") + kChannelNames[c] + "]")) return e;
  }
  if (std::isnan(thickness_mm) || !(thickness_mm > 0.0))
    return FieldError{"thickness", "must be > 0 mm, got " + number(thickness_mm)};
  return std::nullopt;
}

Medium Medium::from_reduced(const Rgb& sigma_a, const Rgb& sigma_s_reduced, double eta,
                            double g) {
  Medium m;
  for (int c = 0; c < 3; ++c) {
    m.sigma_a[c] = sigma_a[c];
    m.sigma_s[c] = sigma_s_reduced[c] / (1.0 - g);
    m.g[c] = g;
    m.eta[c] = eta;
  }
  return m;
}

}  // namespace sss::profiles
