#include "profiles/Presets.h"

#include <array>

namespace sss::profiles {

namespace {

// Jensen, Marschner, Levoy, Hanrahan 2001, Figure 5: σs' and σa in mm^-1 (R, G, B), and
// the diffuse reflectance column. Measured at η = 1.3; marble uses η = 1.5.
constexpr std::array<Preset, 12> kPresets = {{
    {"apple", {2.29, 2.39, 1.97}, {0.0030, 0.0034, 0.046}, {0.85, 0.84, 0.53}, 1.3},
    {"chicken1", {0.15, 0.21, 0.38}, {0.015, 0.077, 0.19}, {0.31, 0.15, 0.10}, 1.3},
    {"chicken2", {0.19, 0.25, 0.32}, {0.018, 0.088, 0.20}, {0.32, 0.16, 0.10}, 1.3},
    {"cream", {7.38, 5.47, 3.15}, {0.0002, 0.0028, 0.0163}, {0.98, 0.90, 0.73}, 1.3},
    {"ketchup", {0.18, 0.07, 0.03}, {0.061, 0.97, 1.45}, {0.16, 0.01, 0.00}, 1.3},
    {"marble", {2.19, 2.62, 3.00}, {0.0021, 0.0041, 0.0071}, {0.83, 0.79, 0.75}, 1.5},
    {"potato", {0.68, 0.70, 0.55}, {0.0024, 0.0090, 0.12}, {0.77, 0.62, 0.21}, 1.3},
    {"skimmilk", {0.70, 1.22, 1.90}, {0.0014, 0.0025, 0.0142}, {0.81, 0.81, 0.69}, 1.3},
    {"skin1", {0.74, 0.88, 1.01}, {0.032, 0.17, 0.48}, {0.44, 0.22, 0.13}, 1.3},
    {"skin2", {1.09, 1.59, 1.79}, {0.013, 0.070, 0.145}, {0.63, 0.44, 0.34}, 1.3},
    {"spectralon", {11.6, 20.4, 14.9}, {0.00, 0.00, 0.00}, {1.00, 1.00, 1.00}, 1.3},
    {"wholemilk", {2.55, 3.21, 3.77}, {0.0011, 0.0024, 0.014}, {0.91, 0.88, 0.76}, 1.3},
}};

}  // namespace

std::span<const Preset> presets() { return kPresets; }

const Preset* find_preset(std::string_view name) {
  for (const Preset& p : kPresets)
    if (p.name == name) return &p;
  return nullptr;
}

Medium preset_medium(const Preset& p) {
  return Medium::from_reduced(p.sigma_a, p.sigma_s_reduced, p.eta, 0.0);
}

std::string preset_names() {
  std::string s;
  for (const Preset& p : kPresets) {
    if (!s.empty()) s += ", ";
    s += p.name;
  }
  return s;
}

}  // namespace sss::profiles
