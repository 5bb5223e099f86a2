#include "profiles/ArtistMapping.h"

#include "profiles/McTable.h"
#include "profiles/McTableProfile.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace sss::profiles {

namespace {

// The medium in reduced-mean-free-path units (σt' = 1) with reduced albedo α'.
Coefficients optical_units(double alpha_p, double eta, double g) {
  return {1.0 - alpha_p, alpha_p / (1.0 - g), g, eta};
}

double total_at(Model model, double alpha_p, double eta, double g, double thickness_mfp,
                const ModelOptions& opt) {
  // mc-table: the interpolated tabulated total, exactly what its profile's
  // total_reflectance() returns, without building R(r) (64 bisection steps per channel).
  // The thickness is ignored as make_profile ignores it (semi-infinite). Any g: the total
  // interpolated over the anisotropic layers, as the profile is.
  if (model == Model::McTable) return mc_table_total_any_g(optical_units(alpha_p, eta, g)).total;
  return make_profile(model, optical_units(alpha_p, eta, g), thickness_mfp, opt)
      ->total_reflectance();
}

const auto str = sss::message_number;

}  // namespace

std::variant<double, FieldError> invert_total_reflectance(Model model, double reflectance,
                                                          double eta, double g,
                                                          double thickness_mfp,
                                                          const ModelOptions& opt) {
  if (model == Model::MonteCarlo)
    return FieldError{"model",
                      "mc has no deterministic total reflectance to invert; choose an "
                      "analytic model for the colour + mean free path mapping"};
  if (!std::isfinite(reflectance) || !(reflectance > 0.0) || !(reflectance < 1.0))
    return FieldError{"color", "must lie strictly between 0 and 1, got " + str(reflectance)};
  // Total reflectance rises monotonically with α'. Near α' = 1 it behaves like
  // 1 - c√(1-α'), so bisect in u = √(1-α'), where it is close to linear.
  // α' ∈ [~0, 1 - 1e-10] (mc-table extrapolates past its last node, McTableProfile.cpp).
  constexpr double u_min = 1e-5;
  constexpr double u_max = 1.0 - 1e-9;
  double hi_total = 0.0, lo_total = 0.0;
  try {
    hi_total = total_at(model, 1.0 - u_min * u_min, eta, g, thickness_mfp, opt);
    lo_total = total_at(model, 1.0 - u_max * u_max, eta, g, thickness_mfp, opt);
  } catch (const std::invalid_argument& e) {
    // The model refuses this geometry (e.g. a multipole slab thinner than one mfp).
    std::string what = e.what();
    const auto colon = what.find(": ");
    if (colon != std::string::npos) return FieldError{what.substr(0, colon), what.substr(colon + 2)};
    return FieldError{"model", what};
  }
  if (reflectance > hi_total)
    return FieldError{"color", str(reflectance) + " is brighter than model " +
                                   std::string(model_name(model)) + " can reach (" +
                                   str(hi_total) + " at this eta and thickness)"};
  if (reflectance < lo_total)
    return FieldError{"color", str(reflectance) + " is darker than model " +
                                   std::string(model_name(model)) + " can reach (" +
                                   str(lo_total) + ")"};
  double lo = u_min, hi = u_max;  // total(lo) >= reflectance >= total(hi)
  for (int i = 0; i < 64 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (total_at(model, 1.0 - mid * mid, eta, g, thickness_mfp, opt) > reflectance)
      lo = mid;
    else
      hi = mid;
  }
  const double u = 0.5 * (lo + hi);
  return 1.0 - u * u;
}

std::variant<Medium, FieldError> medium_from_artist(Model model, const ArtistParameters& p,
                                                    const ModelOptions& opt) {
  Medium m;
  m.thickness_mm = p.thickness_mm;
  for (int c = 0; c < 3; ++c) {
    const std::string ch = std::string("[") + kChannelNames[c] + "]";
    if (!std::isfinite(p.mfp_mm[c]) || !(p.mfp_mm[c] > 0.0))
      return FieldError{"mfp" + ch, "mean free path must be > 0 mm, got " + str(p.mfp_mm[c])};
    // The coefficient range of Coefficients::validate as a length: 1/kMaxCoefficient
    // (1 nm; a decade of margin for sigma_s = alpha' sigma_t' / (1 - g)) to
    // 1/kMinSigmaTReduced (1 km).
    if (p.mfp_mm[c] < 10.0 / kMaxCoefficient || p.mfp_mm[c] > 1.0 / kMinSigmaTReduced)
      return FieldError{"mfp" + ch, "mean free path must lie in [" + str(10.0 / kMaxCoefficient) +
                                        ", " + str(1.0 / kMinSigmaTReduced) + "] mm, got " +
                                        str(p.mfp_mm[c])};
    if (!std::isfinite(p.g) || !(std::fabs(p.g) < 1.0))
      return FieldError{"g", "must lie in (-1, 1), got " + str(p.g)};
    if (!std::isfinite(p.eta) || !(p.eta > 0.0))
      return FieldError{"eta", "must be > 0, got " + str(p.eta)};
    if (p.eta < kEtaMin || p.eta > kEtaMax)
      return FieldError{"eta", "must lie in [" + str(kEtaMin) + ", " + str(kEtaMax) +
                                   "] (the index relative to the outside that the models' "
                                   "Fresnel fits cover), got " + str(p.eta)};
    if (model == Model::Multipole && !(p.thickness_mm > p.mfp_mm[c]))
      return FieldError{"thickness" + ch,
                        "the multipole model needs a slab thicker than one reduced mean free "
                        "path (" + str(p.mfp_mm[c]) + " mm), got " + str(p.thickness_mm) + " mm"};
    auto inverted = invert_total_reflectance(model, p.color[c], p.eta, p.g,
                                             p.thickness_mm / p.mfp_mm[c], opt);
    if (auto* e = std::get_if<FieldError>(&inverted)) {
      e->field += ch;
      return *e;
    }
    const double alpha_p = std::get<double>(inverted);
    const double sigma_tp = 1.0 / p.mfp_mm[c];
    m.sigma_a[c] = (1.0 - alpha_p) * sigma_tp;
    m.sigma_s[c] = alpha_p * sigma_tp / (1.0 - p.g);
    m.g[c] = p.g;
    m.eta[c] = p.eta;
  }
  if (auto e = m.validate()) return *e;
  return m;
}

}  // namespace sss::profiles
