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

  // Checks every field; the error names it with `suffix` appended (e.g. "[G]").
  std::optional<FieldError> validate(const std::string& suffix = "") const;
};

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
  // sigma_s < 0, |g| >= 1, eta <= 0, and a non-positive thickness. The error names the
  // field and channel, e.g. "sigma_a[G]".
  std::optional<FieldError> validate() const;

  static Medium from_reduced(const Rgb& sigma_a, const Rgb& sigma_s_reduced, double eta,
                             double g = 0.0);
};

}  // namespace sss::profiles
