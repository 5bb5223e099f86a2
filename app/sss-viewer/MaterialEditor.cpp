#include "MaterialEditor.h"

#include "profiles/OpenPbr.h"
#include "profiles/Presets.h"
#include "profiles/Profile.h"
#include "scene/ScatterScale.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <utility>

namespace sss::app {

namespace {

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}


// The checks make_sss_material would make on the UI thread's side of an artist source,
// so that a typo shows at once; the model inversion (which may still refuse a colour)
// runs on the worker.
std::optional<FieldError> check_artist(const profiles::ArtistParameters& p) {
  const auto str = sss::message_number;
  for (int c = 0; c < 3; ++c) {
    const std::string ch = std::string("[") + kChannelNames[c] + "]";
    if (!std::isfinite(p.color[c]) || !(p.color[c] > 0.0) || !(p.color[c] < 1.0))
      return FieldError{"color" + ch, "must lie strictly between 0 and 1, got " + str(p.color[c])};
    if (!std::isfinite(p.mfp_mm[c]) || !(p.mfp_mm[c] > 0.0))
      return FieldError{"mfp" + ch, "mean free path must be > 0 mm, got " + str(p.mfp_mm[c])};
  }
  if (!std::isfinite(p.eta) || !(p.eta >= profiles::kEtaMin) || !(p.eta <= profiles::kEtaMax))
    return FieldError{"eta", "must lie in [" + str(profiles::kEtaMin) + ", " + str(profiles::kEtaMax) +
                                 "] (the models' Fresnel fits), got " + str(p.eta)};
  return std::nullopt;
}

}  // namespace

int MaterialEditor::preset_index(std::string_view name) {
  const profiles::Preset* p = profiles::find_preset(name);
  return p == nullptr ? -1 : static_cast<int>(p - profiles::presets().data());
}

int MaterialEditor::model_index(profiles::Model model) {
  const auto& m = models();
  const auto it = std::find(m.begin(), m.end(), model);
  return it == m.end() ? -1 : static_cast<int>(it - m.begin());
}

const std::vector<profiles::Model>& MaterialEditor::models() {
  static const std::vector<profiles::Model> offered = [] {
    std::vector<profiles::Model> out;
    for (profiles::Model m : profiles::kAllModels)
      if (m != profiles::Model::MonteCarlo) out.push_back(m);
    return out;
  }();
  return offered;
}

MaterialEditor::MaterialEditor(const scene::Scene& scene, int separable_taps,
                               FitWorker::Compute compute, bool single_scattering)
    : applied_(scene.materials),
      pending_(scene.materials.size()),
      taps_(separable_taps),
      single_scattering_(single_scattering),
      worker_(std::move(compute)) {
  // Two passes: the SSS materials, then the others (MaterialEditor::edits()).
  for (const bool with_sss : {true, false})
  for (std::size_t i = 0; i < applied_.size(); ++i) {
    const scene::SssMaterial& s = applied_[i].sss;
    if (s.enabled != with_sss) continue;
    MaterialEdit e;
    e.index = i;
    e.enabled = s.enabled;
    e.name = applied_[i].name.empty() ? "material " + std::to_string(i) : applied_[i].name;
    // A stack's model (layered) is not offered: the model it gets if it becomes one medium
    // again (a preset, its layers removed) is the default.
    e.model = std::max(model_index(s.layers.empty() ? s.model : profiles::kDefaultModel), 0);
    e.gaussians = s.gaussians;
    e.scale = static_cast<float>(s.scale);
    e.albedo = s.albedo_mode == scene::AlbedoMode::PrePost ? 1 : 0;
    fill_coefficients(e, s.medium);
    fill_layers(e, s.layers);
    if (const auto* p = std::get_if<scene::PresetSource>(&s.source)) {
      e.kind = SourceKind::Preset;
      e.preset = preset_index(p->name);
      // A material without SSS has the default source (skin1) and no resolved medium.
      if (!s.enabled && e.preset >= 0 && s.layers.empty())
        fill_coefficients(e, profiles::preset_medium(profiles::presets()[std::size_t(e.preset)]));
    } else if (const auto* a = std::get_if<scene::ArtistSource>(&s.source)) {
      e.kind = SourceKind::Artist;
      for (int c = 0; c < 3; ++c) {
        e.color[c] = static_cast<float>(a->parameters.color[c]);
        e.mfp_mm[c] = static_cast<float>(a->parameters.mfp_mm[c]);
      }
      e.artist_eta = static_cast<float>(a->parameters.eta);
    } else if (const auto* o = std::get_if<scene::OpenPbrSource>(&s.source)) {
      e.kind = SourceKind::OpenPbr;
      fill_openpbr(e, o->parameters);
      e.pbr_inversion = o->inversion == profiles::AlbedoInversion::Model ? 1 : 0;
      e.pbr_standard_surface = o->standard_surface;
    } else {
      e.kind = SourceKind::Coefficients;
    }
    e.object_mm = scene::scatter_scale(scene, i).object_mm;
    fill_notes(e);
    edits_.push_back(std::move(e));
  }
  // The plots of the scene's own materials: the same refit the renderer made, off the
  // render thread; its upload changes nothing and is not counted as an edit.
  had_sss_ = !edits_.empty() && edits_.front().enabled;
  if (had_sss_) submit(Clock::time_point{});
}

void MaterialEditor::fill_notes(MaterialEdit& e) const {
  const scene::Material& m = applied_[e.index];
  if (!m.sss.enabled) {  // an opaque surface: nothing scatters
    e.scale_note.clear();
    e.warnings.clear();
    return;
  }
  const scene::ScatterScale s = scene::scatter_scale(m.sss, e.object_mm);
  e.scale_note = scene::scatter_scale_readout(s);
  e.warnings = m.sss.model_warnings();
  if (auto w = scene::scatter_scale_warning(m, s)) e.warnings.push_back(*w);
}

void MaterialEditor::fill_openpbr(MaterialEdit& e, const profiles::OpenPbrSubsurface& p) {
  for (int c = 0; c < 3; ++c) {
    e.pbr_color[c] = static_cast<float>(p.color[c]);
    e.pbr_radius_scale[c] = static_cast<float>(p.radius_scale[c]);
  }
  e.pbr_radius_mm = static_cast<float>(p.radius_mm);
  e.pbr_anisotropy = static_cast<float>(p.anisotropy);
  e.pbr_ior = static_cast<float>(p.ior);
}

void MaterialEditor::fill_coefficients(MaterialEdit& e, const profiles::Medium& m) {
  for (int c = 0; c < 3; ++c) {
    e.sigma_a[c] = static_cast<float>(m.sigma_a[c]);
    e.sigma_s[c] = static_cast<float>(m.sigma_s[c]);
    e.g[c] = static_cast<float>(m.g[c]);
    e.eta[c] = static_cast<float>(m.eta[c]);
  }
  e.thickness_mm = m.is_slab() ? static_cast<float>(m.thickness_mm) : 0.0f;
}

void MaterialEditor::fill_layers(MaterialEdit& e, const profiles::LayerStack& stack) {
  e.layers.clear();
  for (const profiles::Medium& m : stack) {
    LayerEdit l;
    for (int c = 0; c < 3; ++c) {
      l.sigma_a[c] = static_cast<float>(m.sigma_a[c]);
      l.sigma_s[c] = static_cast<float>(m.sigma_s[c]);
      l.g[c] = static_cast<float>(m.g[c]);
    }
    l.thickness_mm = m.is_slab() ? static_cast<float>(m.thickness_mm) : 0.0f;
    e.layers.push_back(l);
  }
  if (stack.empty()) return;
  for (int c = 0; c < 3; ++c) e.eta[c] = static_cast<float>(stack.front().eta[c]);
  e.kind = SourceKind::Coefficients;
}

namespace {

// The stack the layer fields describe. A thickness of 0 is semi-infinite; anything else
// (negative, NaN) goes to validate_layers as typed, so that its error names it.
profiles::LayerStack stack_from_fields(const MaterialEdit& e) {
  profiles::LayerStack out;
  for (const LayerEdit& l : e.layers) {
    profiles::Medium m;
    for (int c = 0; c < 3; ++c) {
      m.sigma_a[c] = l.sigma_a[c];
      m.sigma_s[c] = l.sigma_s[c];
      m.g[c] = l.g[c];
      m.eta[c] = e.eta[c];
    }
    m.thickness_mm =
        l.thickness_mm == 0.0f ? std::numeric_limits<double>::infinity() : double(l.thickness_mm);
    out.push_back(m);
  }
  return out;
}

// The panel's source fields (preset, artist, OpenPBR or coefficients) into s.source;
// false, with e.error, when they are refused.
bool source_from_fields(MaterialEdit& e, double thickness, SssSpec& s) {
  if (e.kind == SourceKind::Preset && e.preset >= 0) {
    s.source = scene::PresetSource{std::string(profiles::presets()[std::size_t(e.preset)].name)};
  } else if (e.kind == SourceKind::Artist) {
    profiles::ArtistParameters p;
    for (int c = 0; c < 3; ++c) {
      p.color[c] = e.color[c];
      p.mfp_mm[c] = e.mfp_mm[c];
    }
    p.eta = e.artist_eta;
    p.thickness_mm = thickness;
    if (auto err = check_artist(p)) {
      e.error = err->what();
      return false;
    }
    s.source = scene::ArtistSource{p};
  } else if (e.kind == SourceKind::OpenPbr) {
    scene::OpenPbrSource o;
    for (int c = 0; c < 3; ++c) {
      o.parameters.color[c] = e.pbr_color[c];
      o.parameters.radius_scale[c] = e.pbr_radius_scale[c];
    }
    o.parameters.radius_mm = e.pbr_radius_mm;
    o.parameters.anisotropy = e.pbr_anisotropy;
    o.parameters.ior = e.pbr_ior;
    o.inversion = e.pbr_inversion == 1 ? profiles::AlbedoInversion::Model : profiles::AlbedoInversion::VanDeHulst;
    o.standard_surface = e.pbr_standard_surface;
    o.thickness_mm = thickness;
    if (auto err = profiles::validate(o.parameters)) {
      e.error = err->what();
      return false;
    }
    s.source = o;
  } else {
    e.kind = SourceKind::Coefficients;
    profiles::Medium m;
    for (int c = 0; c < 3; ++c) {
      m.sigma_a[c] = e.sigma_a[c];
      m.sigma_s[c] = e.sigma_s[c];
      m.g[c] = e.g[c];
      m.eta[c] = e.eta[c];
    }
    m.thickness_mm = thickness;
    s.source = scene::CoefficientSource{m};
  }
  return true;
}

// Whether s can be built (false, with e.error when it says why), before it reaches the
// worker.
bool spec_is_valid(MaterialEdit& e, const SssSpec& s) {
  // Everything but the artist inversion is cheap: check it here, so that bad input never
  // reaches the worker (and the frame stays as it is).
  const bool inverts = e.kind == SourceKind::Artist || (e.kind == SourceKind::OpenPbr && e.pbr_inversion == 1);
  if (!inverts) {
    auto made = scene::make_sss_material(s.source, s.model, s.gaussians, s.scale, s.albedo_mode);
    if (auto* err = std::get_if<FieldError>(&made)) {
      e.error = err->what();
      return false;
    }
    // The model's own limits (multipole: a finite slab). Only multipole has any, and
    // building a pbd profile here would cost ~10 ms (its total reflectance).
    if (s.model == profiles::Model::Multipole) {
      try {
        const profiles::RgbProfile check(s.model,
                                         std::get<scene::SssMaterial>(made).effective_medium());
      } catch (const std::invalid_argument& ex) {
        e.error = ex.what();
        return false;
      }
    }
  } else if (!profiles::valid_gaussian_count(s.gaussians) || !std::isfinite(s.scale) || !(s.scale > 0.0)) {
    auto made = scene::make_sss_material(scene::PresetSource{"skin1"}, s.model, s.gaussians,
                                         s.scale, s.albedo_mode);
    if (auto* err = std::get_if<FieldError>(&made)) e.error = err->what();
    return false;
  }
  return true;
}

}  // namespace

bool MaterialEditor::select_preset(std::size_t edit, int preset) {
  MaterialEdit& e = edits_.at(edit);
  const auto all = profiles::presets();
  if (preset < 0 || preset >= static_cast<int>(all.size())) {
    e.error = "preset: no preset " + std::to_string(preset);
    return false;
  }
  e.kind = SourceKind::Preset;
  e.preset = preset;
  e.layers.clear();  // a preset is one medium: it replaces a stack
  fill_coefficients(e, profiles::preset_medium(all[static_cast<std::size_t>(preset)]));
  return apply(edit);
}

bool MaterialEditor::select_model(std::size_t edit, int model) {
  MaterialEdit& e = edits_.at(edit);
  if (model < 0 || model >= static_cast<int>(models().size())) {
    e.error = "model: no model " + std::to_string(model);
    return false;
  }
  if (!e.layers.empty()) {
    e.error = "model: a stack's model is layered; remove its layers down to one (or choose a "
              "preset) to choose another";
    return false;
  }
  e.model = model;
  return apply(edit);
}

bool MaterialEditor::set_source_kind(std::size_t edit, SourceKind kind) {
  MaterialEdit& e = edits_.at(edit);
  if (kind == e.kind) return true;
  if (!e.layers.empty() && (kind == SourceKind::Artist || kind == SourceKind::OpenPbr)) {
    e.error = std::string(kind == SourceKind::Artist ? "artist: a colour + mfp" : "openpbr: OpenPBR's subsurface") +
              " describes one medium, not a stack; edit the layers' coefficients";
    return false;
  }
  const scene::Material& current = applied_[e.index];
  const profiles::Medium& m = current.sss.medium;
  if (kind == SourceKind::Artist) {
    // The colour that reproduces the current look: the model's total reflectance (scale
    // does not change it), and the reduced mfp per channel.
    try {
      Rgb total = e.total_reflectance;
      if (!(total[0] > 0.0))  // not known yet: pbd's total costs ~10 ms here
        total = current.sss.profile().total_reflectance();
      for (int c = 0; c < 3; ++c) {
        e.color[c] = std::clamp(static_cast<float>(total[c]), 0.001f, 0.999f);
        e.mfp_mm[c] = static_cast<float>(m.channel(c).mfp_reduced());
      }
      e.artist_eta = static_cast<float>(m.eta[0]);
    } catch (const std::exception&) {
      // keep the fields as they were
    }
  } else if (kind == SourceKind::OpenPbr) {
    // The spec's forward map of the current medium: with the spec's inversion it is the
    // same medium (within its rounded constants), so the look stays.
    const profiles::OpenPbrSubsurface p = profiles::openpbr_from_medium(m);
    fill_openpbr(e, p);
    for (int c = 0; c < 3; ++c) e.pbr_color[c] = std::clamp(e.pbr_color[c], 0.001f, 0.999f);
    e.pbr_inversion = 0;
  } else if (kind == SourceKind::Preset) {
    return select_preset(edit, e.preset >= 0 ? e.preset : preset_index("skin1"));
  } else {
    fill_coefficients(e, m);
  }
  e.kind = kind;
  return apply(edit);
}

std::optional<SssSpec> MaterialEditor::spec_from_fields(MaterialEdit& e) {
  SssSpec s;
  s.model = models()[static_cast<std::size_t>(e.model)];
  s.gaussians = e.gaussians;
  s.scale = e.scale;
  s.albedo_mode = e.albedo == 1 ? scene::AlbedoMode::PrePost : scene::AlbedoMode::PostScatter;
  const double thickness =
      e.thickness_mm > 0.0f ? double(e.thickness_mm) : std::numeric_limits<double>::infinity();
  if (!source_from_fields(e, thickness, s) || !spec_is_valid(e, s)) return std::nullopt;
  return s;
}

std::optional<SssSpec> MaterialEditor::layered_spec(MaterialEdit& e) {
  SssSpec s;
  s.gaussians = e.gaussians;
  s.scale = e.scale;
  s.albedo_mode = e.albedo == 1 ? scene::AlbedoMode::PrePost : scene::AlbedoMode::PostScatter;
  s.layers = stack_from_fields(e);
  // The stack's checks and the material's (gaussians, scale) are cheap: made here, so that
  // bad input never reaches the worker.
  auto made = scene::make_layered_sss_material(s.layers, s.gaussians, s.scale, s.albedo_mode);
  if (auto* err = std::get_if<FieldError>(&made)) {
    e.error = err->what();
    return std::nullopt;
  }
  s.model = profiles::Model::Layered;
  s.source = std::get<scene::SssMaterial>(made).source;
  fill_coefficients(e, s.layers.front());  // the top layer's fields follow the stack
  return s;
}

bool MaterialEditor::set_enabled(std::size_t edit, bool on) {
  MaterialEdit& e = edits_.at(edit);
  if (e.enabled == on) return true;
  e.enabled = on;
  if (apply(edit)) return true;
  e.enabled = !on;  // the fields did not resolve: the switch stays where it was
  return false;
}

bool MaterialEditor::apply(std::size_t edit) {
  const auto edited = Clock::now();
  MaterialEdit& e = edits_.at(edit);
  e.eta_offer.reset();
  std::optional<SssSpec> spec;
  if (!e.enabled) {  // the fields are not read: they wait for the switch
    spec.emplace();
    spec->enabled = false;
  } else {
    spec = e.layers.empty() ? spec_from_fields(e) : layered_spec(e);
  }
  if (!spec) return false;
  e.error.clear();
  pending_[e.index] = std::move(spec);
  submit(edited);
  return true;
}

void MaterialEditor::submit(Clock::time_point edited) {
  FitRequest request;
  request.materials = applied_;
  request.specs = pending_;
  request.separable_taps = taps_;
  request.single_scattering = single_scattering_;
  request.edited = edited;
  request.previous = applied_data_;
  running_max_frame_ms_ = 0.0;
  worker_.submit(std::move(request));
}

bool MaterialEditor::update(renderer::Renderer& r) {
  std::optional<FitResult> result = worker_.take();
  if (!result) return false;
  // The newest request: every pending spec is in it.
  for (auto& p : pending_) p.reset();
  if (!result->error.empty()) {
    for (MaterialEdit& e : edits_)
      if (result->error_material < 0 || e.index == std::size_t(result->error_material))
        e.error = result->error;
    return false;
  }
  if (result->data.separable_taps != r.options().separable_taps ||
      result->data.single_scattering != r.options().single_scattering) {
    // The taps or the single-scattering switch changed meanwhile: fit the same edits again
    // (their specs go back to pending, unless a newer edit of the material is there).
    taps_ = r.options().separable_taps;
    single_scattering_ = r.options().single_scattering;
    for (std::size_t i = 0; i < pending_.size() && i < result->request.specs.size(); ++i)
      if (!pending_[i]) pending_[i] = result->request.specs[i];
    submit(result->request.edited);
    return false;
  }
  auto data = std::make_shared<const renderer::MaterialData>(result->data);
  const auto start = Clock::now();
  try {
    r.set_materials(result->request.materials, std::move(result->data));
  } catch (const std::exception& ex) {
    for (MaterialEdit& e : edits_) e.error = ex.what();
    return false;
  }
  const double upload_ms = ms_since(start);
  applied_ = std::move(result->request.materials);
  applied_data_ = std::move(data);
  for (MaterialEdit& e : edits_) {
    if (e.index < result->plots.size() && result->plots[e.index])
      e.plot = std::move(result->plots[e.index]);
    if (e.index < applied_data_->profiles.size()) {  // the CPU's value, not the GPU packing
      const auto& profile = applied_data_->profiles[e.index];
      e.total_reflectance = profile ? profile->kernel.total_reflectance : Rgb{1.0, 1.0, 1.0};
    }
    if (e.index < applied_.size()) fill_notes(e);
  }
  if (result->request.edited != Clock::time_point{}) {
    latency_.fit_ms = result->fit_ms;
    latency_.upload_ms = upload_ms;
    edited_ = result->request.edited;
    awaiting_present_ = true;
  }
  return true;
}

void MaterialEditor::frame_presented(double frame_ms) {
  if (worker_.busy() || awaiting_present_)
    running_max_frame_ms_ = std::max(running_max_frame_ms_, frame_ms);
  if (!awaiting_present_) return;
  awaiting_present_ = false;
  latency_.edit_to_frame_ms = ms_since(edited_);
  latency_.max_frame_ms = running_max_frame_ms_;
  ++latency_.edits;
}

}  // namespace sss::app
