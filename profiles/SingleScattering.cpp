#include "profiles/SingleScattering.h"

#include "profiles/Fresnel.h"
#include "profiles/Integrate.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sss::profiles {

double refracted_cosine(double cos_outside, double eta) {
  const double c = std::clamp(cos_outside, 0.0, 1.0);
  return std::sqrt(std::max(0.0, 1.0 - (1.0 - c * c) / (eta * eta)));
}

double henyey_greenstein(double g, double cos_theta) {
  const double d = 1.0 + g * g - 2.0 * g * cos_theta;
  return (1.0 - g * g) / (4.0 * std::numbers::pi * d * std::sqrt(d));
}

double single_scattering_brdf(const Coefficients& c, double cos_i, double cos_o, double cos_dphi) {
  if (!(cos_i > 0.0) || !(cos_o > 0.0)) return 0.0;
  const double mi = refracted_cosine(cos_i, c.eta), mo = refracted_cosine(cos_o, c.eta);
  const double si = std::sqrt(std::max(0.0, 1.0 - mi * mi)), so = std::sqrt(std::max(0.0, 1.0 - mo * mo));
  const double cos_theta = -mi * mo + si * so * std::clamp(cos_dphi, -1.0, 1.0);
  return fresnel_transmittance(cos_i, c.eta) * fresnel_transmittance(cos_o, c.eta) * c.albedo() *
         henyey_greenstein(c.g, cos_theta) / (c.eta * c.eta * (mi + mo));
}

double single_scattering_exit_density(const Coefficients& c, double cos_i, double cos_o) {
  if (!(cos_i > 0.0) || !(cos_o > 0.0)) return 0.0;
  // Per unit power entered: L⁽¹⁾ μo dφ dμo / (E μi F_t(η, μi)).
  const double phi_integral = integrate(
      [&](double phi) { return single_scattering_brdf(c, cos_i, cos_o, std::cos(phi)); }, 0.0,
      2.0 * std::numbers::pi, 8, 8);
  return phi_integral * cos_o / fresnel_transmittance(cos_i, c.eta);
}

}  // namespace sss::profiles
