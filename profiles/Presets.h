// Measured media of Jensen et al. 2001 (Figure 5 of "A practical model for subsurface
// light transport"): reduced scattering σs' and absorption σa in mm^-1 for R, G, B, and
// the diffuse reflectance they list. g = 0, so σs = σs' (as the table gives only σs').
#pragma once

#include "profiles/Medium.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace sss::profiles {

struct Preset {
  std::string_view name;
  Rgb sigma_s_reduced;
  Rgb sigma_a;
  Rgb published_reflectance;  // the table's "diffuse reflectance" column
  double eta;
};

std::span<const Preset> presets();
const Preset* find_preset(std::string_view name);
Medium preset_medium(const Preset& p);
std::string preset_names();  // "apple, chicken1, ..." for messages

}  // namespace sss::profiles
