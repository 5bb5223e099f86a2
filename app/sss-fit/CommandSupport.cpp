#include "CommandSupport.h"

#include "profiles/McTableProfile.h"
#include "image/AtomicFile.h"
#include "scene/SssLayers.h"

#include <cstdio>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace sss::app {

int usage_error(const FieldError& e) { return usage_error(e.what()); }

int usage_error(const std::string& message) {
  std::cerr << "sss-fit: error: " << message << '\n';
  return kExitUsage;
}

profiles::ModelOptions model_options(const CommonArgs& a) {
  profiles::ModelOptions o;
  if (a.pbd_samples > 0) o.pbd_samples = a.pbd_samples;
  o.mc_photons = a.photons;
  o.mc_seed = a.seed;
  o.mc_threads = a.threads;
  // Model mc's walk takes seconds to minutes (2^20 photons of cream: 4 min on 2 cores).
  o.mc_progress = [](double f) { progress_bar("Monte Carlo profile", f); };
  return o;
}

std::optional<profiles::Model> resolve_model(const std::string& name) {
  if (name == profiles::model_name(profiles::Model::Layered)) {
    usage_error("--model: layered needs the stack: give --layers FILE.json");
    return std::nullopt;
  }
  auto m = profiles::parse_model(name);
  if (!m) usage_error("--model: unknown model '" + name + "'; known: " + profiles::model_names());
  return m;
}

bool ProfileSource::has_transmittance() const {
  if (layers) return !layers->empty() && layers->back().is_slab();
  return medium.is_slab() && model == profiles::Model::Multipole;
}

profiles::RgbProfile ProfileSource::make_profile(const profiles::ModelOptions& opt) const {
  if (layers) {
    for (const std::string& w : profiles::layered_g_warnings(*layers))
      std::cerr << "sss-fit: warning: " << w << '\n';
    try {
      return profiles::make_layered_rgb_profile(*layers, opt);
    } catch (const std::invalid_argument& e) {
      // A stack validate_layers passes may still be one the layered model cannot describe
      // (a layer thinner than its reduced mean free path): say which file.
      throw std::invalid_argument("--layers " + layers_file + ": " + e.what());
    }
  }
  if (model == profiles::Model::McTable) {
    // g outside the tabulated range: the lookup falls back to the similarity relation.
    for (const std::string& w : profiles::mc_table_g_warnings(medium))
      std::cerr << "sss-fit: warning: " << w << '\n';
  }
  return profiles::RgbProfile(model, medium, opt);
}

std::vector<profiles::Coefficients> ProfileSource::channel_media(int c) const {
  std::vector<profiles::Coefficients> out;
  if (!layers) return {medium.channel(c)};
  for (const profiles::Medium& m : *layers) out.push_back(m.channel(c));
  return out;
}

profiles::MonteCarloResult ProfileSource::monte_carlo(int c, profiles::MonteCarloOptions mc) const {
  if (layers) return profiles::run_layered_monte_carlo(profiles::channel_layers(*layers, c), mc);
  mc.thickness_mm = medium.thickness_mm;
  return profiles::run_monte_carlo(medium.channel(c), mc);
}

namespace {

// "layers FILE (3 layers: 0.1 + 0.8 mm over a semi-infinite base)"
std::string describe_layers(const std::string& path, const profiles::LayerStack& stack) {
  std::ostringstream d;
  d << "layers " << path << " (" << stack.size() << (stack.size() == 1 ? " layer" : " layers");
  std::string sep = ": ";
  for (const profiles::Medium& m : stack) {
    if (!m.is_slab()) break;
    d << sep << m.thickness_mm;
    sep = " + ";
  }
  if (stack.back().is_slab())
    d << " mm)";
  else
    d << (stack.size() == 1 ? ": " : " mm over a ") << "semi-infinite base)";
  return d.str();
}

// The MEDIUM option that is given, for the message that --layers excludes it.
std::optional<std::string> medium_option_given(const MediumArgs& m) {
  for (auto [name, value] :
       {std::pair{"--preset", &m.preset}, std::pair{"--sigma-a", &m.sigma_a},
        std::pair{"--sigma-s", &m.sigma_s}, std::pair{"--color", &m.color},
        std::pair{"--mfp", &m.mfp}, std::pair{"--g", &m.g}, std::pair{"--eta", &m.eta},
        std::pair{"--thickness", &m.thickness}})
    if (!value->empty()) return std::string(name);
  return std::nullopt;
}

}  // namespace

std::optional<ProfileSource> resolve_source(const CommonArgs& a, const profiles::ModelOptions& opt,
                                            bool with_model) {
  ProfileSource src;
  if (!a.layers.empty()) {
    if (const auto given = medium_option_given(a.medium)) {
      usage_error("--layers: cannot be combined with " + *given +
                  ": the layers file gives every layer's medium");
      return std::nullopt;
    }
    const std::string layered{profiles::model_name(profiles::Model::Layered)};
    if (with_model && a.model_given && a.model != layered) {
      usage_error("--model: --layers implies --model layered; got '" + a.model + "'");
      return std::nullopt;
    }
    auto parsed = scene::parse_sss_layers_file(a.layers);
    if (auto* e = std::get_if<FieldError>(&parsed)) {
      // "--layers FILE: layers[1].sigma_a[2]: ...", or "--layers FILE: cannot be opened ...".
      e->field = "--layers " + a.layers + (e->field == a.layers ? "" : ": " + e->field);
      usage_error(*e);
      return std::nullopt;
    }
    src.model = profiles::Model::Layered;
    src.model_name = layered;
    src.layers = std::move(std::get<profiles::LayerStack>(parsed));
    src.layers_file = a.layers;
    src.description = describe_layers(a.layers, *src.layers);
    return src;
  }
  profiles::Model model = profiles::kDefaultModel;
  if (with_model) {
    const auto m = resolve_model(a.model);
    if (!m) return std::nullopt;
    model = *m;
  }
  auto resolved = resolve_medium(a.medium, model, opt);
  if (auto* e = std::get_if<FieldError>(&resolved)) {
    usage_error(*e);
    return std::nullopt;
  }
  src.model = model;
  src.model_name = with_model ? a.model : std::string(profiles::model_name(model));
  src.medium = std::get<ResolvedMedium>(resolved).medium;
  src.description = std::get<ResolvedMedium>(resolved).description;
  return src;
}

nlohmann::json layers_json(const profiles::LayerStack& stack) {
  nlohmann::json out = nlohmann::json::array();
  for (const profiles::Medium& m : stack) {
    nlohmann::json layer = {{"sigma_a", to_json(m.sigma_a)},
                            {"sigma_s", to_json(m.sigma_s)},
                            {"g", to_json(m.g)},
                            {"eta", to_json(m.eta)}};
    if (m.is_slab()) layer["thickness_mm"] = m.thickness_mm;
    out.push_back(std::move(layer));
  }
  return out;
}

nlohmann::json to_json(const Rgb& v) { return nlohmann::json::array({v[0], v[1], v[2]}); }

bool write_output(const std::string& path, const std::string& bytes) {
  try {
    image::write_file_atomically(path, bytes);
    return true;
  } catch (const image::WriteError& e) {
    std::cerr << "sss-fit: error: " << e.what() << '\n';
    return false;
  }
}

void progress_bar(const char* what, double fraction) {
  static const bool tty = ::isatty(STDERR_FILENO) != 0;
  static std::mutex mutex;
  static int last = -1;
  std::lock_guard lock(mutex);
  const int pct = static_cast<int>(fraction * 100.0 + 0.5);
  if (pct == last) return;
  if (!tty) {  // a log or a pipe: a line every 10%, no carriage returns
    if (pct / 10 == last / 10 && last >= 0) return;
    last = pct;
    std::fprintf(stderr, "sss-fit: %s %d%%\n", what, pct / 10 * 10);
    if (pct >= 100) last = -1;
    std::fflush(stderr);
    return;
  }
  last = pct;
  const int filled = pct * 30 / 100;
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", what, filled, "==============================",
               30 - filled, "", pct);
  if (pct >= 100) {
    std::fputc('\n', stderr);
    last = -1;
  }
  std::fflush(stderr);
}

}  // namespace sss::app
