// The MEDIUM options shared by every sss-fit command (DESIGN.md §4):
//   --preset NAME | --sigma-a R,G,B --sigma-s R,G,B | --color R,G,B --mfp R,G,B
//   | --subsurface-color R,G,B --subsurface-radius MM [--subsurface-radius-scale R,G,B]
//     (OpenPBR) | --subsurface-color R,G,B --subsurface-radius R,G,B [--subsurface-scale MM]
//     (Standard Surface) [--albedo-inversion van-de-hulst|model]
//   [--g G] [--eta E] [--thickness MM]
#pragma once

#include "profiles/Medium.h"
#include "profiles/OpenPbr.h"
#include "profiles/Profile.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <variant>

namespace sss::app {

struct MediumArgs {
  std::string preset, sigma_a, sigma_s, color, mfp, g, eta, thickness;
  // OpenPBR / Standard Surface (profiles/OpenPbr.h); --g is the anisotropy, --eta the
  // specular ior.
  std::string subsurface_color, subsurface_radius, subsurface_radius_scale, subsurface_scale,
      albedo_inversion;
};

void add_medium_options(CLI::App& cmd, MediumArgs& args);

struct ResolvedMedium {
  profiles::Medium medium;
  std::string description;  // for titles, headers and JSON
  // Given as OpenPBR's or Standard Surface's parameters: what they were, so that a
  // material keeps them (and Export writes them back).
  std::optional<profiles::OpenPbrSubsurface> openpbr;
  profiles::AlbedoInversion inversion = profiles::AlbedoInversion::VanDeHulst;
  bool standard_surface = false;
};

// Builds and validates the medium. `model` is the model whose total reflectance the
// artist parametrization (--color/--mfp) inverts. Errors name the option and field.
std::variant<ResolvedMedium, FieldError> resolve_medium(const MediumArgs& args,
                                                        profiles::Model model,
                                                        const profiles::ModelOptions& opt);

// "a,b,c" or a single number for all three channels.
std::variant<Rgb, FieldError> parse_rgb(const std::string& option, const std::string& text);
std::variant<double, FieldError> parse_number(const std::string& option, const std::string& text);

}  // namespace sss::app
