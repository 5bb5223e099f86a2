// The MEDIUM options shared by every sss-fit command (DESIGN.md §4):
//   --preset NAME | --sigma-a R,G,B --sigma-s R,G,B | --color R,G,B --mfp R,G,B
//   [--g G] [--eta E] [--thickness MM]
#pragma once

#include "profiles/Medium.h"
#include "profiles/Profile.h"

#include <CLI/CLI.hpp>

#include <string>
#include <variant>

namespace sss::app {

struct MediumArgs {
  std::string preset, sigma_a, sigma_s, color, mfp, g, eta, thickness;
};

void add_medium_options(CLI::App& cmd, MediumArgs& args);

struct ResolvedMedium {
  profiles::Medium medium;
  std::string description;  // for titles, headers and JSON
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
