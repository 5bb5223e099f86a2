#include "profiles/Fresnel.h"

#include "profiles/Integrate.h"

#include <cmath>
#include <stdexcept>

namespace sss::profiles {

double fresnel_dielectric(double cos_i, double eta_rel) {
  cos_i = std::fmin(std::fabs(cos_i), 1.0);
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta_rel * eta_rel);
  if (sin2_t >= 1.0) return 1.0;  // total internal reflection
  const double cos_t = std::sqrt(1.0 - sin2_t);
  // Fresnel equations for s and p polarization (Born & Wolf §1.5), averaged.
  const double rs = (cos_i - eta_rel * cos_t) / (cos_i + eta_rel * cos_t);
  const double rp = (eta_rel * cos_i - cos_t) / (eta_rel * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

double fresnel_moment(int i, double eta) {
  if (i < 0 || i > 4) throw std::invalid_argument("fresnel_moment: order must be in [0, 4]");
  if (!(eta > 0.0)) throw std::invalid_argument("fresnel_moment: eta must be > 0");
  // Light inside the medium meets the boundary to the outside: relative index 1/eta.
  const double eta_rel = 1.0 / eta;
  // Below the critical cosine μc = √(1 - 1/η²) (η > 1) everything reflects: ∫0^μc μ^i dμ.
  const double mu_c = eta > 1.0 ? std::sqrt(1.0 - 1.0 / (eta * eta)) : 0.0;
  const double tir = std::pow(mu_c, i + 1) / (i + 1);
  // Above it Fr has a square-root kink at μc; with μ = μc + (1 - μc) s², the integrand
  // is smooth in s and Gauss–Legendre converges fast.
  const double span = 1.0 - mu_c;
  const double rest = integrate(
      [&](double s) {
        const double mu = mu_c + span * s * s;
        return fresnel_dielectric(mu, eta_rel) * std::pow(mu, i) * 2.0 * span * s;
      },
      0.0, 1.0, 8, 32);
  return tir + rest;
}

// d'Eon 2012 ("A better dipole") fits of 2C1 and 3C2, here divided by 2 and 3 so they
// are the plain moments ∫Fr μ dμ and ∫Fr μ² dμ (the same values pbrt-v3 uses).
double fresnel_moment1_fit(double eta) {
  const double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
  if (eta < 1.0)
    return 0.45966 - 1.73965 * eta + 3.37668 * e2 - 3.904945 * e3 + 2.49277 * e4 -
           0.68441 * e5;
  return -4.61686 + 11.1136 * eta - 10.4646 * e2 + 5.11455 * e3 - 1.27198 * e4 +
         0.12746 * e5;
}

double fresnel_moment2_fit(double eta) {
  const double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
  if (eta < 1.0)
    return 0.27614 - 0.87350 * eta + 1.12077 * e2 - 0.65095 * e3 + 0.07883 * e4 +
           0.04860 * e5;
  const double r = 1.0 / eta, r2 = r * r, r3 = r2 * r;
  return -547.033 + 45.3087 * r3 - 218.725 * r2 + 458.843 * r + 404.557 * eta -
         189.519 * e2 + 54.9327 * e3 - 9.00603 * e4 + 0.63942 * e5;
}

double fresnel_transmittance(double cos_outside, double eta) {
  return 1.0 - fresnel_dielectric(cos_outside, eta);
}

double fresnel_exit_normalization(double eta) {
  if (!(eta > 0.0)) throw std::invalid_argument("fresnel_exit_normalization: eta must be > 0");
  // Renderers ask per pixel, almost always for the same few η: the last answer per
  // thread saves the quadrature (256 Fresnel evaluations).
  thread_local double last_eta = -1.0, last_c = 1.0;
  if (eta != last_eta) {
    last_c = 1.0 - 2.0 * fresnel_moment(1, 1.0 / eta);
    last_eta = eta;
  }
  return last_c;
}

double fresnel_diffuse_reflectance_fit(double eta) {
  return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
}

}  // namespace sss::profiles
