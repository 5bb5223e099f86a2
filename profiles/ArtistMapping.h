// The artist's parametrization: a diffuse colour (the total diffuse reflectance wanted
// per channel) and a mean free path per channel → optical coefficients, by inverting the
// chosen model's total reflectance in the reduced albedo α' (as pbrt's
// SubsurfaceFromDiffuse does for PBD). The mean free path is the reduced one, 1/σt'.
#pragma once

#include "profiles/Medium.h"
#include "profiles/Profile.h"

#include <variant>

namespace sss::profiles {

struct ArtistParameters {
  Rgb color{};     // total diffuse reflectance per channel, in (0, 1)
  Rgb mfp_mm{};    // reduced mean free path per channel, > 0
  double eta = 1.3;
  double g = 0.0;
  double thickness_mm = std::numeric_limits<double>::infinity();
};

// The reduced albedo α' whose total reflectance under `model` is `reflectance`, for a
// medium with the given η, g and thickness in reduced mean free paths.
std::variant<double, FieldError> invert_total_reflectance(Model model, double reflectance,
                                                          double eta, double g,
                                                          double thickness_mfp,
                                                          const ModelOptions& opt = {});

// Fails (naming "color[G]", "mfp[B]", ...) for values out of range or colours the model
// cannot reach.
std::variant<Medium, FieldError> medium_from_artist(Model model, const ArtistParameters& p,
                                                    const ModelOptions& opt = {});

}  // namespace sss::profiles
