#include "MaterialOverrides.h"

#include "profiles/Presets.h"
#include "scene/ScatterScale.h"
#include "scene/SssLayers.h"

#include <cmath>
#include <set>
#include <sstream>

namespace sss::app {

namespace {
// The first MEDIUM option given, as typed ("--preset"), or nullptr when none is.
const char* first_medium_option(const MediumArgs& m) {
  const std::pair<const std::string*, const char*> options[] = {
      {&m.preset, "--preset"}, {&m.sigma_a, "--sigma-a"}, {&m.sigma_s, "--sigma-s"},
      {&m.color, "--color"},   {&m.mfp, "--mfp"},         {&m.g, "--g"},
      {&m.eta, "--eta"},       {&m.thickness, "--thickness"},
      {&m.subsurface_color, "--subsurface-color"}, {&m.subsurface_radius, "--subsurface-radius"},
      {&m.subsurface_radius_scale, "--subsurface-radius-scale"},
      {&m.subsurface_scale, "--subsurface-scale"}, {&m.albedo_inversion, "--albedo-inversion"}};
  for (const auto& [value, name] : options)
    if (!value->empty()) return name;
  return nullptr;
}

bool any_medium(const MediumArgs& m) { return first_medium_option(m) != nullptr; }

// A medium given as OpenPBR's or Standard Surface's parameters keeps them as its source.
scene::OpenPbrSource openpbr_source(const ResolvedMedium& r) {
  scene::OpenPbrSource s;
  s.parameters = *r.openpbr;
  s.inversion = r.inversion;
  s.standard_surface = r.standard_surface;
  s.thickness_mm = r.medium.thickness_mm;
  return s;
}

// SssMaterial::scale's range, as make_sss_material checks it: checked here first so that
// the message names the option.
bool valid_scale(double scale) { return std::isfinite(scale) && scale > 0.0; }

// The model a material is remade under: the given one, else its own, else (a stack, or a
// material that did not scatter) the default.
profiles::Model model_for(const scene::SssMaterial& own, std::optional<profiles::Model> given) {
  return given.value_or(own.enabled && own.layers.empty() ? own.model : profiles::kDefaultModel);
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

constexpr const char* kSpecKeys =
    "preset, sigma-a, sigma-s, color, mfp, g, eta, thickness, subsurface-color, subsurface-radius, "
    "subsurface-radius-scale, subsurface-scale, albedo-inversion, model, gaussians, albedo, scale";

std::variant<double, FieldError> parse_scale(const std::string& option, const std::string& text) {
  auto v = parse_number(option, text);
  if (auto* e = std::get_if<FieldError>(&v)) return *e;
  const double scale = std::get<double>(v);
  if (!valid_scale(scale)) return FieldError{option, "must be a finite number > 0, got '" + text + "'"};
  return scale;
}

// The materials a spec's TARGET names: `all`, an index, or every material of that name.
std::variant<std::vector<std::size_t>, FieldError> match_target(const scene::Scene& scene,
                                                                const SssMaterialSpec& spec) {
  std::vector<std::size_t> out;
  if (spec.target == "all") {
    for (std::size_t i = 0; i < scene.materials.size(); ++i) out.push_back(i);
  } else {
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
      if (scene.materials[i].name == spec.target) out.push_back(i);
    const bool digits = spec.target.find_first_not_of("0123456789") == std::string::npos;
    if (out.empty() && digits && spec.target.size() < 10) {
      const std::size_t i = std::stoul(spec.target);
      if (i < scene.materials.size()) out.push_back(i);
    }
  }
  if (out.empty())
    return FieldError{"--sss-material " + spec.text,
                      scene.materials.empty()
                          ? std::string("the scene has no materials")
                          : "no material named or numbered '" + spec.target +
                                "'; the scene's materials: " + material_list(scene)};
  return out;
}

// Keep the source as the user gave it, so that the panel shows it and Export writes it:
// a preset by name, an artist colour and mfp as such (mc inverts through mc-table, see
// resolve_medium, so it keeps the coefficients), OpenPBR's parameters, coefficients
// otherwise.
scene::SssSource source_as_given(const MediumArgs& a, profiles::Model use, const ResolvedMedium& r) {
  if (!a.preset.empty() && a.eta.empty() && a.thickness.empty()) return scene::PresetSource{a.preset};
  if (!a.color.empty() && use != profiles::Model::MonteCarlo) {
    profiles::ArtistParameters p;
    p.color = std::get<Rgb>(parse_rgb("color", a.color));  // resolve_medium parsed them
    p.mfp_mm = std::get<Rgb>(parse_rgb("mfp", a.mfp));
    p.eta = r.medium.eta[0];
    p.g = r.medium.g[0];
    p.thickness_mm = r.medium.thickness_mm;
    return scene::ArtistSource{p};
  }
  if (r.openpbr) return openpbr_source(r);
  return scene::CoefficientSource{r.medium};
}

// One key=value item of a spec into `spec`; an error names the key.
std::optional<FieldError> set_spec_key(SssMaterialSpec& spec, const std::string& field, const std::string& key,
                                       const std::string& value) {
  MediumArgs& m = spec.medium;
  if (key == "preset") m.preset = value;
  else if (key == "sigma-a") m.sigma_a = value;
  else if (key == "sigma-s") m.sigma_s = value;
  else if (key == "color") m.color = value;
  else if (key == "mfp") m.mfp = value;
  else if (key == "g") m.g = value;
  else if (key == "eta") m.eta = value;
  else if (key == "thickness") m.thickness = value;
  else if (key == "subsurface-color") m.subsurface_color = value;
  else if (key == "subsurface-radius") m.subsurface_radius = value;
  else if (key == "subsurface-radius-scale") m.subsurface_radius_scale = value;
  else if (key == "subsurface-scale") m.subsurface_scale = value;
  else if (key == "albedo-inversion") m.albedo_inversion = value;
  else if (key == "model") spec.model = value;
  else if (key == "albedo") spec.albedo = value;
  else if (key == "scale") {
    auto v = parse_scale(field + ": scale", value);
    if (auto* e = std::get_if<FieldError>(&v)) return *e;
    spec.scale = std::get<double>(v);
  } else if (key == "gaussians") {
    auto v = parse_number(field + ": gaussians", value);
    if (auto* e = std::get_if<FieldError>(&v)) return *e;
    const double n = std::get<double>(v);
    if (!profiles::valid_gaussian_count(n))
      return FieldError{field + ": gaussians", profiles::gaussian_count_rule() + ", got '" + value + "'"};
    spec.gaussians = int(n);
  } else {
    return FieldError{field + ": " + key, std::string("unknown key (keys: ") + kSpecKeys + ")"};
  }
  return std::nullopt;
}

// The material a spec makes of `m`: its keys, then the global options, then m's own
// values (when it scatters already), then the defaults.
std::variant<scene::SssMaterial, FieldError> material_from_spec(
    const scene::Material& m, const SssMaterialSpec& spec, const MaterialOverrideArgs& global,
    std::optional<profiles::Model> global_model, std::optional<scene::AlbedoMode> global_albedo) {
  const std::string field = "--sss-material " + spec.text;
  const bool had = m.sss.enabled;
  std::optional<profiles::Model> model = global_model;
  if (!spec.model.empty()) {
    model = profiles::parse_model(spec.model);
    if (!model)
      return FieldError{field + ": model", "unknown model '" + spec.model + "' (expected one of " +
                                               profiles::model_names() + ")"};
  }
  std::optional<scene::AlbedoMode> albedo = global_albedo;
  if (!spec.albedo.empty()) {
    albedo = scene::parse_albedo_mode(spec.albedo);
    if (!albedo)
      return FieldError{field + ": albedo", "expected post-scatter or pre-post, got '" + spec.albedo + "'"};
  }
  const int gaussians = spec.gaussians.value_or(global.gaussians.value_or(had ? m.sss.gaussians : scene::kDefaultGaussians));
  const double scale = spec.scale.value_or(global.scale.value_or(had ? m.sss.scale : 1.0));
  const scene::AlbedoMode albedo_mode = albedo.value_or(had ? m.sss.albedo_mode : scene::AlbedoMode::PostScatter);
  const auto named = [&](FieldError e) {
    e.field = field + ": " + (e.field.rfind("--", 0) == 0 ? e.field.substr(2) : e.field);
    return e;
  };

  if (!any_medium(spec.medium)) {
    if (!had)
      return FieldError{field, "material '" + m.name + "' has no subsurface medium yet: give a "
                               "preset, sigma-a and sigma-s, or color and mfp"};
    // Its own medium, with the spec's model and settings; a stack keeps its layers.
    auto made = !m.sss.layers.empty() && !model
                    ? scene::make_layered_sss_material(m.sss.layers, gaussians, scale, albedo_mode)
                    : scene::make_sss_material(m.sss.source, model_for(m.sss, model), gaussians, scale, albedo_mode);
    if (auto* e = std::get_if<FieldError>(&made)) return named(*e);
    return std::get<scene::SssMaterial>(std::move(made));
  }

  const profiles::Model use = model_for(m.sss, model);
  auto resolved = resolve_medium(spec.medium, use, profiles::ModelOptions{});
  if (auto* e = std::get_if<FieldError>(&resolved)) return named(*e);
  auto made = scene::make_sss_material(source_as_given(spec.medium, use, std::get<ResolvedMedium>(resolved)), use,
                                       gaussians, scale, albedo_mode);
  if (auto* e = std::get_if<FieldError>(&made)) return named(*e);
  return std::get<scene::SssMaterial>(std::move(made));
}
}  // namespace

std::variant<SssMaterialSpec, FieldError> parse_sss_material_spec(const std::string& text) {
  SssMaterialSpec spec;
  spec.text = text;
  const std::string field = "--sss-material " + text;
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    return FieldError{"--sss-material",
                      "expected TARGET=SPEC (TARGET: a material's name or index, or all; SPEC: "
                      "off, a preset, or key=value items separated by ';'), got '" + text + "'"};
  spec.target = text.substr(0, eq);
  const std::string rest = text.substr(eq + 1);
  if (trim(rest) == "off") {
    spec.off = true;
    return spec;
  }
  std::vector<std::string> items;
  std::stringstream ss(rest);
  for (std::string item; std::getline(ss, item, ';');) items.push_back(trim(item));
  std::set<std::string> seen;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string& item = items[i];
    if (item.empty()) return FieldError{field, "an empty item between ';'"};
    const auto k = item.find('=');
    std::string key = trim(item.substr(0, k)), value = k == std::string::npos ? "" : trim(item.substr(k + 1));
    if (k == std::string::npos) {
      if (i != 0)
        return FieldError{field, "expected key=value, got '" + item + "' (keys: " + kSpecKeys + ")"};
      value = key;  // a bare preset name first
      key = "preset";
    }
    if (!seen.insert(key).second) return FieldError{field + ": " + key, "given twice"};
    if (value.empty()) return FieldError{field + ": " + key, "has no value"};
    if (auto e = set_spec_key(spec, field, key, value)) return *e;
  }
  return spec;
}

std::string material_list(const scene::Scene& scene) {
  std::string out;
  for (std::size_t i = 0; i < scene.materials.size(); ++i)
    out += (i ? ", " : "") + std::to_string(i) + " '" + scene.materials[i].name + "'" +
           (scene.materials[i].sss.enabled ? " (subsurface)" : "");
  return out.empty() ? "none" : out;
}

void add_material_override_options(CLI::App& app, MaterialOverrideArgs& args) {
  app.add_option("--model", args.model,
                 "Profile model for every SSS material: dipole | better-dipole | pbd | burley | "
                 "multipole | mc | mc-table | qd (default: each material's own; " +
                     std::string(profiles::model_name(profiles::kDefaultModel)) +
                     " where the scene names none)");
  app.add_option("--gaussians", args.gaussians, "Gaussians per fit, 1..8");
  app.add_option("--albedo", args.albedo,
                 "Where SSS materials apply their colour: post-scatter | pre-post (sqrt before "
                 "and after scattering)");
  app.add_option("--layers", args.layers,
                 "A stack of layers for every SSS material instead of MEDIUM: FILE.json holding "
                 "{\"layers\": [...]} (model layered; README \"Layered materials\")");
  app.add_option("--scale", args.scale,
                 "SssMaterial scale for every SSS material: the object scatters as if it were "
                 "SCALE times larger (a distance d scatters as d x SCALE), > 0. Lower it for a "
                 "model in metres that should look like a small object (the opposite of "
                 "Blender's Subsurface Scale)");
  app.add_option("--sss-material", args.sss_material,
                 "TARGET=SPEC, repeatable: gives subsurface scattering to materials of any "
                 "glTF (with or without extras.sss). TARGET: a material's name, its index, or "
                 "all. SPEC: off (opaque), a preset, or key=value items separated by ';' "
                 "(quote them): preset, sigma-a, sigma-s, color, mfp, g, eta, thickness as the "
                 "MEDIUM options, and model, gaussians, albedo, scale. Its keys win over the "
                 "global options for those materials. Example: 'all=marble;scale=0.05'");
  add_medium_options(app, args.medium);
}

namespace {

// The options that apply to every SSS material the --sss-material specs leave alone.
struct GlobalOverrides {
  std::optional<profiles::Model> model;
  std::optional<scene::AlbedoMode> albedo;
  bool medium = false;  // a MEDIUM option was given
  std::optional<profiles::LayerStack> layers;
  bool any(const MaterialOverrideArgs& args) const {
    return model || args.gaussians || medium || albedo || layers || args.scale;
  }
};

std::variant<GlobalOverrides, FieldError> parse_globals(const MaterialOverrideArgs& args) {
  GlobalOverrides out;
  if (!args.model.empty()) {
    out.model = profiles::parse_model(args.model);
    if (!out.model)
      return FieldError{"--model", "unknown model '" + args.model + "' (expected one of " +
                                       profiles::model_names() + ")"};
  }
  if (args.gaussians && !profiles::valid_gaussian_count(*args.gaussians))
    return FieldError{"--gaussians", profiles::gaussian_count_rule() + ", got " + std::to_string(*args.gaussians)};
  if (args.scale && !valid_scale(*args.scale))
    return FieldError{"--scale", "must be a finite number > 0, got " + message_number(*args.scale)};
  if (!args.albedo.empty()) {
    out.albedo = scene::parse_albedo_mode(args.albedo);
    if (!out.albedo)
      return FieldError{"--albedo", "expected post-scatter or pre-post, got '" + args.albedo + "'"};
  }
  out.medium = any_medium(args.medium);
  if (!args.layers.empty()) {
    if (out.medium || out.model)
      return FieldError{"--layers", std::string("cannot be combined with ") +
                                        (out.model ? "--model" : "the MEDIUM options") +
                                        ": the layers are the medium, and the model is layered"};
    auto parsed = scene::parse_sss_layers_file(args.layers);
    if (auto* e = std::get_if<FieldError>(&parsed)) {
      // A file error names the file already; a field inside it gets the file in front.
      const std::string field = e->field == args.layers ? e->field : args.layers + ": " + e->field;
      return FieldError{"--layers " + field, e->message};
    }
    out.layers = std::get<profiles::LayerStack>(std::move(parsed));
  }

  return out;
}

// --sss-material onto `materials` (by_spec marks those a spec set). Parsed and matched
// before anything changes, so an error leaves the scene as it was loaded.
std::optional<FieldError> apply_specs(const scene::Scene& scene, const MaterialOverrideArgs& args,
                                      const GlobalOverrides& g, std::vector<scene::Material>& materials,
                                      std::vector<bool>& by_spec, int& changed) {
  const std::optional<profiles::Model>& model = g.model;
  const std::optional<scene::AlbedoMode>& albedo = g.albedo;
  std::vector<std::pair<SssMaterialSpec, std::vector<std::size_t>>> specs;
  for (const std::string& text : args.sss_material) {
    auto spec = parse_sss_material_spec(text);
    if (auto* e = std::get_if<FieldError>(&spec)) return *e;
    auto matched = match_target(scene, std::get<SssMaterialSpec>(spec));
    if (auto* e = std::get_if<FieldError>(&matched)) return *e;
    specs.emplace_back(std::get<SssMaterialSpec>(std::move(spec)),
                       std::get<std::vector<std::size_t>>(std::move(matched)));
  }
  for (const auto& [spec, matched] : specs)
    for (std::size_t i : matched) {
      scene::Material& m = materials[i];
      if (spec.off) {
        m.sss = scene::SssMaterial{};
      } else {
        auto made = material_from_spec(m, spec, args, model, albedo);
        if (auto* e = std::get_if<FieldError>(&made)) return *e;
        m.sss = std::get<scene::SssMaterial>(std::move(made));
      }
      changed += by_spec[i] ? 0 : 1;
      by_spec[i] = true;
    }
  return std::nullopt;
}

// A global option that would change nothing is an error: the scene has no SSS material,
// or the specs set every one and a medium was given.
std::optional<FieldError> check_globals_match(const scene::Scene& scene, const MaterialOverrideArgs& args,
                                              const GlobalOverrides& g,
                                              const std::vector<scene::Material>& materials,
                                              const std::vector<bool>& by_spec) {
  const bool medium = g.medium;
  const auto& model = g.model;
  const auto& albedo = g.albedo;
  const auto& layers = g.layers;
  const bool any_global = g.any(args);
  std::size_t sss_count = 0, left = 0;
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].sss.enabled) {
      ++sss_count;
      left += by_spec[i] ? 0 : 1;
    }
  if (any_global && (sss_count == 0 || ((medium || layers) && left == 0))) {
    const char* option = layers ? "--layers"
                         : medium ? first_medium_option(args.medium)
                         : model ? "--model"
                         : args.gaussians ? "--gaussians"
                         : albedo ? "--albedo"
                                  : "--scale";
    std::string scene_name = scene.name.empty() ? std::string("the scene") : "'" + scene.name + "'";
    return FieldError{option, sss_count == 0
        ? "matches no material: " + scene_name + " has no subsurface material (its materials: " +
              material_list(scene) + "). Give one subsurface scattering with --sss-material "
              "NAME|INDEX|all=SPEC, e.g. --sss-material 'all=marble'"
        : "matches no material: every subsurface material of " + scene_name +
              " is set by --sss-material, whose SPEC gives the medium"};
  }
  return std::nullopt;
}

// The global options onto one SSS material the specs left alone.
std::optional<FieldError> apply_globals(const MaterialOverrideArgs& args, const GlobalOverrides& g,
                                        scene::Material& m) {
  const bool medium = g.medium;
  const auto& model = g.model;
  const auto& albedo = g.albedo;
  const auto& layers = g.layers;
  const double scale = args.scale.value_or(m.sss.scale);
  // A stack given, or kept: the layered material with the other overrides applied.
  const bool keep_stack = !m.sss.layers.empty() && !medium && !model;
  if (layers || keep_stack) {
    scene::SssMaterial s = m.sss;
    if (layers) {  // parse_sss_layers_file validated the stack, and s its other fields
      auto made = scene::make_layered_sss_material(*layers, s.gaussians, scale, s.albedo_mode);
      if (auto* e = std::get_if<FieldError>(&made)) return FieldError{"--layers " + args.layers, e->what()};
      s = std::get<scene::SssMaterial>(std::move(made));
    }
    s.gaussians = args.gaussians.value_or(s.gaussians);
    s.albedo_mode = albedo.value_or(s.albedo_mode);
    s.scale = scale;
    m.sss = std::move(s);
    return std::nullopt;
  }
  // A medium or model given to a layered material replaces its stack.
  const profiles::Model use_model = model_for(m.sss, model);
  scene::SssSource source = m.sss.source;
  if (medium) {
    profiles::ModelOptions options;
    auto resolved = resolve_medium(args.medium, use_model, options);
    if (auto* e = std::get_if<FieldError>(&resolved)) return *e;
    const auto& r = std::get<ResolvedMedium>(resolved);
    source = r.openpbr ? openpbr_source(r) : scene::SssSource{scene::CoefficientSource{r.medium}};
  }
  auto made = scene::make_sss_material(source, use_model, args.gaussians.value_or(m.sss.gaussians),
                                       scale, albedo.value_or(m.sss.albedo_mode));
  if (auto* e = std::get_if<FieldError>(&made)) return *e;
  m.sss = std::get<scene::SssMaterial>(made);
  return std::nullopt;
}

}  // namespace

std::variant<int, FieldError> apply_material_overrides(scene::Scene& scene,
                                                       const MaterialOverrideArgs& args) {
  auto parsed = parse_globals(args);
  if (auto* e = std::get_if<FieldError>(&parsed)) return *e;
  const GlobalOverrides& g = std::get<GlobalOverrides>(parsed);
  std::vector<scene::Material> materials = scene.materials;
  std::vector<bool> by_spec(materials.size(), false);
  int changed = 0;
  if (auto e = apply_specs(scene, args, g, materials, by_spec, changed)) return *e;
  if (auto e = check_globals_match(scene, args, g, materials, by_spec)) return *e;
  for (std::size_t i = 0; i < materials.size() && g.any(args); ++i) {
    if (!materials[i].sss.enabled || by_spec[i]) continue;
    if (auto e = apply_globals(args, g, materials[i])) return *e;
    ++changed;
  }

  scene.materials = std::move(materials);
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const scene::Material& m = scene.materials[i];
    if (!by_spec[i] || !m.sss.enabled) continue;
    if (m.metallic > 0.0f)
      scene.warnings.push_back("material '" + m.name + "' is metallic (" + message_number(m.metallic) +
                               "): its subsurface light is scaled by 1 - metallic = " +
                               message_number(1.0 - m.metallic) +
                               " (set pbrMetallicRoughness.metallicFactor to 0 for a dielectric)");
  }
  return changed;
}

void add_material_warnings(scene::Scene& scene, std::uint32_t height) {
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const scene::Material& m = scene.materials[i];
    if (!m.sss.enabled) continue;
    for (const std::string& w : m.sss.model_warnings())
      scene.warnings.push_back("material '" + m.name + "': " + w);
    if (auto w = scene::scatter_scale_warning(scene, i, height)) scene.warnings.push_back(*w);
  }
}

}  // namespace sss::app
