#include "MaterialOverrides.h"

#include "profiles/Presets.h"
#include "renderer/scene/SssLayers.h"

namespace sss::app {

namespace {
bool any_medium(const MediumArgs& m) {
  return !m.preset.empty() || !m.sigma_a.empty() || !m.sigma_s.empty() || !m.color.empty() ||
         !m.mfp.empty() || !m.g.empty() || !m.eta.empty() || !m.thickness.empty();
}
}  // namespace

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
  add_medium_options(app, args.medium);
}

std::variant<int, FieldError> apply_material_overrides(scene::Scene& scene,
                                                       const MaterialOverrideArgs& args) {
  std::optional<profiles::Model> model;
  if (!args.model.empty()) {
    model = profiles::parse_model(args.model);
    if (!model)
      return FieldError{"--model", "unknown model '" + args.model + "' (expected one of " +
                                       profiles::model_names() + ")"};
  }
  if (args.gaussians && (*args.gaussians < scene::kMinGaussians ||
                         *args.gaussians > scene::kMaxGaussians))
    return FieldError{"--gaussians", "must be in 1..8, got " + std::to_string(*args.gaussians)};
  std::optional<scene::AlbedoMode> albedo;
  if (!args.albedo.empty()) {
    albedo = scene::parse_albedo_mode(args.albedo);
    if (!albedo)
      return FieldError{"--albedo", "expected post-scatter or pre-post, got '" + args.albedo + "'"};
  }
  const bool medium = any_medium(args.medium);
  std::optional<profiles::LayerStack> layers;
  if (!args.layers.empty()) {
    if (medium || model)
      return FieldError{"--layers", std::string("cannot be combined with ") +
                                        (model ? "--model" : "the MEDIUM options") +
                                        ": the layers are the medium, and the model is layered"};
    auto parsed = scene::parse_sss_layers_file(args.layers);
    if (auto* e = std::get_if<FieldError>(&parsed)) {
      // A file error names the file already; a field inside it gets the file in front.
      const std::string field = e->field == args.layers ? e->field : args.layers + ": " + e->field;
      return FieldError{"--layers " + field, e->message};
    }
    layers = std::get<profiles::LayerStack>(std::move(parsed));
  }
  if (!model && !args.gaussians && !medium && !albedo && !layers) return 0;

  int changed = 0;
  for (scene::Material& m : scene.materials) {
    if (!m.sss.enabled) continue;
    // A stack given, or kept: the layered material with the other overrides applied.
    const bool keep_stack = !m.sss.layers.empty() && !medium && !model;
    if (layers || keep_stack) {
      scene::SssMaterial s = m.sss;
      if (layers) {  // parse_sss_layers_file validated the stack, and s its other fields
        auto made = scene::make_layered_sss_material(*layers, s.gaussians, s.scale, s.albedo_mode);
        if (auto* e = std::get_if<FieldError>(&made)) return FieldError{"--layers " + args.layers, e->what()};
        s = std::get<scene::SssMaterial>(std::move(made));
      }
      s.gaussians = args.gaussians.value_or(s.gaussians);
      s.albedo_mode = albedo.value_or(s.albedo_mode);
      m.sss = std::move(s);
      ++changed;
      continue;
    }
    // A medium or model given to a layered material replaces its stack.
    const profiles::Model use_model =
        model.value_or(m.sss.layers.empty() ? m.sss.model : profiles::kDefaultModel);
    scene::SssSource source = m.sss.source;
    if (medium) {
      profiles::ModelOptions options;
      auto resolved = resolve_medium(args.medium, use_model, options);
      if (auto* e = std::get_if<FieldError>(&resolved)) return *e;
      source = scene::CoefficientSource{std::get<ResolvedMedium>(resolved).medium};
    }
    auto made = scene::make_sss_material(source, use_model, args.gaussians.value_or(m.sss.gaussians),
                                         m.sss.scale, albedo.value_or(m.sss.albedo_mode));
    if (auto* e = std::get_if<FieldError>(&made)) return *e;
    m.sss = std::get<scene::SssMaterial>(made);
    ++changed;
  }
  return changed;
}

}  // namespace sss::app
