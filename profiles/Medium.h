// Medium: the optical coefficients of a homogeneous translucent medium, per RGB channel.
//
// Units (DESIGN.md §3): coefficients in mm^-1, lengths in mm. Reduced quantities follow
// the similarity relation sigma_s' = sigma_s (1 - g) (Wyman et al. 1989; lecture slide
// "Principle of Similarity").
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>

namespace sss {

using Rgb = std::array<double, 3>;
inline constexpr const char* kChannelNames[3] = {"R", "G", "B"};

// An input error that names the offending field ("sigma_a[G]", "preset", ...).
struct FieldError {
  std::string field;
  std::string message;
  std::string what() const { return field + ": " + message; }
};

// A number as error messages print it (shortest iostream form: 0.5, 1e-06, nan, inf).
std::string message_number(double v);

}  // namespace sss

namespace sss::profiles {

// The coefficients of one wavelength band. Every model works on these.
struct Coefficients {
  double sigma_a = 0.0;  // absorption, mm^-1
  double sigma_s = 0.0;  // scattering, mm^-1
  double g = 0.0;        // Henyey-Greenstein mean cosine, (-1, 1)
  double eta = 1.0;      // refractive index of the medium relative to the outside

  double sigma_t() const { return sigma_a + sigma_s; }
  double albedo() const { return sigma_s / sigma_t(); }
  double sigma_s_reduced() const { return sigma_s * (1.0 - g); }
  double sigma_t_reduced() const { return sigma_a + sigma_s_reduced(); }
  double albedo_reduced() const { return sigma_s_reduced() / sigma_t_reduced(); }
  // Reduced (transport) mean free path 1/sigma_t', in mm: the length unit of diffusion.
  double mfp_reduced() const { return 1.0 / sigma_t_reduced(); }
  // Classical effective transport coefficient sqrt(3 sigma_a sigma_t') (Jensen et al. 2001).
  double sigma_tr_classical() const;

  // Checks every field; the error names it with `suffix` appended (e.g. "[G]"). The
  // ranges are those of kEtaMin..kEtaMax and kMaxCoefficient..kMinSigmaTReduced below.
  std::optional<FieldError> validate(const std::string& suffix = "") const;
};

// One channel of one layer of a stack (profiles/Layered.h): the layer's coefficients and
// its thickness in mm (> 0; infinity for a semi-infinite base, which only the last layer
// of a stack may be). The interfaces between layers are index-matched: every layer of a
// stack has the same eta (validate_layers in Layered.h says why).
struct Layer {
  Coefficients c;
  double thickness_mm = std::numeric_limits<double>::infinity();
};

// The refractive index every model accepts, relative to the outside. Below 1 the
// Groenhuis fit of Fdr that the classical dipole and the multipole use turns negative
// (Fdr(0.9) = -0.26, so the boundary term A = (1+Fdr)/(1-Fdr) < 1, a boundary that
// gives light back), and above 2.5 d'Eon's polynomial fits of the Fresnel moments that
// the better dipole, PBD and Burley use leave the exact moments (first moment +26% at
// eta 3, and the better dipole's profile goes negative there); on [1, 2.5] both moment
// fits stay within 0.0025 of fresnel_moment's numerical integral (tested in
// tests/profiles/test_medium.cpp). Real media in air: water 1.33, skin ~1.4, glass 1.5,
// diamond 2.42.
inline constexpr double kEtaMin = 1.0, kEtaMax = 2.5;
// Coefficients above 1e6 mm^-1 (a mean free path under 1 nm) or a reduced extinction
// below 1e-6 mm^-1 (a reduced mean free path over 1 km) are outside what a renderer in mm
// can use; beyond them the closed forms overflow (sigma_tr = sqrt(3 sigma_a sigma_t'))
// and the profiles return inf/NaN (measured: 1e150 and 1e-300 mm^-1 do).
inline constexpr double kMaxCoefficient = 1e6, kMinSigmaTReduced = 1e-6;
// sigma_a / sigma_t' below this (a reduced albedo within 1e-12 of 1) is refused like
// sigma_a = 0: the diffusion length 1/sigma_tr is then over 5e5 reduced mean free paths.
inline constexpr double kMinAbsorptionRatio = 1e-12;

// An RGB medium, optionally a finite slab.
struct Medium {
  Rgb sigma_a{};
  Rgb sigma_s{};
  Rgb g{};
  Rgb eta{1.3, 1.3, 1.3};
  // Slab thickness in mm; infinity means a semi-infinite medium.
  double thickness_mm = std::numeric_limits<double>::infinity();

  Coefficients channel(int c) const { return {sigma_a[c], sigma_s[c], g[c], eta[c]}; }
  bool is_slab() const { return thickness_mm < std::numeric_limits<double>::infinity(); }

  // Rejects NaN/Inf, sigma_a <= 0 (an albedo of 1 has no finite diffusion length),
  // sigma_s < 0, |g| >= 1, eta outside [kEtaMin, kEtaMax], coefficients outside
  // kMaxCoefficient / kMinSigmaTReduced / kMinAbsorptionRatio, and a non-positive thickness. The error names the
  // field and channel, e.g. "sigma_a[G]".
  std::optional<FieldError> validate() const;

  static Medium from_reduced(const Rgb& sigma_a, const Rgb& sigma_s_reduced, double eta,
                             double g = 0.0);
};

}  // namespace sss::profiles
