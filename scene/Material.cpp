#include "scene/Material.h"

#include "profiles/McTableProfile.h"
#include "profiles/Presets.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sss::scene {

namespace {

const auto str = sss::message_number;

}  // namespace

std::string_view albedo_mode_name(AlbedoMode mode) {
  return mode == AlbedoMode::PrePost ? "pre-post" : "post-scatter";
}

std::optional<AlbedoMode> parse_albedo_mode(std::string_view name) {
  if (name == "post-scatter") return AlbedoMode::PostScatter;
  if (name == "pre-post") return AlbedoMode::PrePost;
  return std::nullopt;
}

profiles::Medium SssMaterial::effective_medium() const {
  profiles::Medium m = medium;
  for (int c = 0; c < 3; ++c) {
    m.sigma_a[c] *= scale;
    m.sigma_s[c] *= scale;
  }
  m.thickness_mm /= scale;  // stays infinite for a semi-infinite medium
  return m;
}

profiles::LayerStack SssMaterial::effective_layers() const {
  profiles::LayerStack out = layers;
  for (profiles::Medium& m : out) {
    for (int c = 0; c < 3; ++c) {
      m.sigma_a[c] *= scale;
      m.sigma_s[c] *= scale;
    }
    m.thickness_mm /= scale;
  }
  return out;
}

double SssMaterial::effective_thickness_mm() const {
  if (layers.empty()) return effective_medium().thickness_mm;
  double t = 0.0;
  for (const profiles::Medium& m : layers) t += m.thickness_mm;
  return t / scale;
}

bool SssMaterial::transmits() const {
  return effective_thickness_mm() < std::numeric_limits<double>::infinity();
}

profiles::RgbProfile SssMaterial::profile(const profiles::ModelOptions& opt) const {
  if (!layers.empty()) return profiles::make_layered_rgb_profile(effective_layers(), opt);
  return profiles::RgbProfile(model, effective_medium(), opt);
}

std::vector<std::string> SssMaterial::model_warnings() const {
  // The scale does not change g.
  if (!layers.empty()) return profiles::layered_g_warnings(layers);
  if (model != profiles::Model::McTable) return {};
  return profiles::mc_table_g_warnings(medium);
}

std::variant<profiles::Medium, FieldError> resolve_medium(const SssSource& source,
                                                          profiles::Model model) {
  if (const auto* p = std::get_if<PresetSource>(&source)) {
    const profiles::Preset* preset = profiles::find_preset(p->name);
    if (!preset)
      return FieldError{"preset", "unknown preset \"" + p->name +
                                      "\"; expected one of " + profiles::preset_names()};
    const profiles::Medium m = profiles::preset_medium(*preset);
    if (auto e = m.validate())
      return FieldError{"preset", "\"" + p->name + "\" cannot be rendered: " + e->what()};
    return m;
  }
  if (const auto* c = std::get_if<CoefficientSource>(&source)) {
    if (auto e = c->medium.validate()) return *e;
    return c->medium;
  }
  if (const auto* o = std::get_if<OpenPbrSource>(&source)) {
    auto m = profiles::medium_from_openpbr(o->parameters, o->inversion, model);
    if (auto* e = std::get_if<FieldError>(&m)) return *e;
    auto medium = std::get<profiles::Medium>(m);
    medium.thickness_mm = o->thickness_mm;
    return medium;
  }
  const auto& artist = std::get<ArtistSource>(source);
  auto m = profiles::medium_from_artist(model, artist.parameters);
  if (auto* e = std::get_if<FieldError>(&m)) return *e;
  return std::get<profiles::Medium>(m);
}

std::variant<SssMaterial, FieldError> make_sss_material(SssSource source,
                                                        profiles::Model model, int gaussians,
                                                        double scale, AlbedoMode albedo_mode) {
  if (!profiles::valid_gaussian_count(gaussians))
    return FieldError{"gaussians", profiles::gaussian_count_rule() + ", got " + std::to_string(gaussians)};
  if (!std::isfinite(scale) || !(scale > 0.0))
    return FieldError{"scale", "must be a finite number > 0, got " + str(scale)};
  auto medium = resolve_medium(source, model);
  if (auto* e = std::get_if<FieldError>(&medium)) return *e;
  SssMaterial s;
  s.enabled = true;
  s.source = std::move(source);
  s.medium = std::get<profiles::Medium>(medium);
  s.model = model;
  s.gaussians = gaussians;
  s.scale = scale;
  s.albedo_mode = albedo_mode;
  return s;
}

std::variant<SssMaterial, FieldError> make_layered_sss_material(profiles::LayerStack layers,
                                                                int gaussians, double scale,
                                                                AlbedoMode albedo_mode) {
  if (auto e = profiles::validate_layers(layers)) return *e;
  auto made = make_sss_material(CoefficientSource{layers.front()}, profiles::kDefaultModel,
                                gaussians, scale, albedo_mode);
  if (auto* e = std::get_if<FieldError>(&made)) return *e;
  auto& s = std::get<SssMaterial>(made);
  s.model = profiles::Model::Layered;
  s.layers = std::move(layers);
  return made;
}

SssMaterial preset_sss_material(std::string_view preset) {
  auto s = make_sss_material(PresetSource{std::string(preset)});
  if (auto* e = std::get_if<FieldError>(&s)) throw std::invalid_argument(e->what());
  return std::get<SssMaterial>(s);
}

}  // namespace sss::scene
