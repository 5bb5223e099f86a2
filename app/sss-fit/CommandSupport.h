// Helpers shared by the sss-fit commands.
#pragma once

#include "Commands.h"

#include "profiles/Layered.h"
#include "profiles/MonteCarlo.h"
#include "profiles/Profile.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace sss::app {

profiles::ModelOptions model_options(const CommonArgs& a);
// The model named by --model, or nullopt after printing the usage error.
std::optional<profiles::Model> resolve_model(const std::string& name);

// What a command's profile is made of: one medium (the MEDIUM options, with --model) or a
// stack of layers (--layers FILE.json, model layered).
struct ProfileSource {
  profiles::Model model = profiles::kDefaultModel;
  std::string model_name;   // as printed: --model's text, or "layered"
  std::string description;  // the medium or the stack, for titles, headers and JSON
  profiles::Medium medium;  // without --layers
  std::optional<profiles::LayerStack> layers;
  std::string layers_file;  // --layers FILE.json, for messages

  // Whether the profile has a far face and so a T(r): a multipole slab, or a stack whose
  // last layer is finite.
  bool has_transmittance() const;
  // Throws std::invalid_argument (naming the field, after "--layers FILE: " for a stack)
  // for inputs the model refuses.
  profiles::RgbProfile make_profile(const profiles::ModelOptions& opt) const;
  // The coefficients of channel c: one medium's, or every layer's, top first.
  std::vector<profiles::Coefficients> channel_media(int c) const;
  // Channel c's Monte Carlo walk of the same medium or stack (`mc.thickness_mm` is set
  // here from the medium; a stack carries its own thicknesses).
  profiles::MonteCarloResult monte_carlo(int c, profiles::MonteCarloOptions mc) const;
};

// The source the command line names, or nullopt after printing the usage error. With
// --layers no MEDIUM option may be given, and --model (when `with_model`: the command
// has one) only as "layered". Without --layers, the MEDIUM options resolved for --model
// (kDefaultModel where the command has no --model).
std::optional<ProfileSource> resolve_source(const CommonArgs& a, const profiles::ModelOptions& opt,
                                            bool with_model);
// A stack as parse_sss_layers reads it back: one object per layer, top first, every field
// an array of 3; thickness_mm left out on a semi-infinite last layer.
nlohmann::json layers_json(const profiles::LayerStack& stack);
nlohmann::json to_json(const Rgb& v);
// Writes `bytes` atomically; on failure prints the error and returns false.
bool write_output(const std::string& path, const std::string& bytes);
// A progress bar on stderr while a long job runs, only when stderr is a terminal.
void progress_bar(const char* what, double fraction);

}  // namespace sss::app
