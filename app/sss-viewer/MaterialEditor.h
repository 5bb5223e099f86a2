// MaterialEditor: the state and logic of the viewer's material panel, without ImGui. The
// widgets (Ui.cpp) edit the fields of a MaterialEdit and call the methods below; tests
// call the same methods, so a scripted edit goes through the code path of a click.
//
// An edit is checked at once (a bad number shows its FieldError and changes nothing),
// then resolved and fitted on the FitWorker; update() on the render thread uploads the
// newest finished fit before the next frame (Renderer::set_materials(materials, data))
// and frame_presented() closes the edit → frame latency.
#pragma once

#include "FitWorker.h"
#include "ProfilePlot.h"

#include "profiles/OpenPbr.h"
#include "renderer/Renderer.h"
#include "scene/Scene.h"

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sss::app {

enum class SourceKind { Preset, Coefficients, Artist, OpenPbr };

// One layer of a stack as the editor shows it (issue 19): σa, σs, g per channel R, G, B in
// mm^-1, and the thickness in mm (0: semi-infinite, the last layer only). The stack's η is
// MaterialEdit::eta, for every layer: the interfaces between layers are index-matched
// (profiles/Layered.h). `preset` indexes profiles::presets() while the layer's coefficients
// are that preset's (chosen in its row); -1 once they are typed, or read from a file.
struct LayerEdit {
  std::array<float, 3> sigma_a{}, sigma_s{}, g{};
  float thickness_mm = 0.0f;
  int preset = -1;
};

struct MaterialEdit {
  std::size_t index = 0;  // into the scene's materials
  std::string name;
  // The "enable subsurface" switch (issue 20). Every material of the scene has an edit;
  // one without SSS starts off, its fields on skin1 at scale 1 (what `--sss-material
  // NAME=skin1` gives), ready for the switch.
  bool enabled = true;
  SourceKind kind = SourceKind::Preset;
  int preset = -1;  // into profiles::presets() while kind == Preset
  int model = 0;    // into MaterialEditor::models()
  int gaussians = scene::kDefaultGaussians;
  float scale = 1.0f;
  int albedo = 0;  // 0 post-scatter, 1 pre-post
  // A layered material's stack, top first (empty: one medium). Its model is layered, its
  // source coefficients; the fields below then hold its top layer (and eta the stack's).
  std::vector<LayerEdit> layers;
  // The coefficient fields (mm^-1), per channel R, G, B; thickness 0: semi-infinite.
  std::array<float, 3> sigma_a{}, sigma_s{}, g{}, eta{1.3f, 1.3f, 1.3f};
  float thickness_mm = 0.0f;
  // The artist fields: diffuse colour (total reflectance) and reduced mfp in mm.
  std::array<float, 3> color{0.5f, 0.5f, 0.5f}, mfp_mm{1.0f, 1.0f, 1.0f};
  float artist_eta = 1.3f;
  // OpenPBR's subsurface fields (profiles/OpenPbr.h): colour (linear Rec.709), radius mm,
  // radius scale, anisotropy, specular ior; the inversion 0 van de Hulst (the spec's),
  // 1 the model's total reflectance. A Standard Surface source is shown as OpenPBR's
  // equivalent and written back as Standard Surface's.
  std::array<float, 3> pbr_color{0.8f, 0.8f, 0.8f}, pbr_radius_scale{1.0f, 0.5f, 0.25f};
  float pbr_radius_mm = 1.0f, pbr_anisotropy = 0.0f, pbr_ior = 1.5f;
  int pbr_inversion = 0;
  bool pbr_standard_surface = false;
  Rgb total_reflectance{};          // of the material the frame shows (0: not known yet)
  std::string error;                // the last edit's FieldError, shown in red
  // Set while `error` is a layer preset refused for its η: the choice, which
  // set_layer_preset(edit, layer, preset, true) makes with the preset's η for the whole
  // stack (the panel's button under the refusal). Cleared by the next apply().
  struct EtaOffer {
    std::size_t layer = 0;
    int preset = -1;
    std::array<float, 3> eta{};
  };
  std::optional<EtaOffer> eta_offer;
  // The material's scale against its object (issue 20): the bounding diameter of what it
  // is drawn on, mm (0: not drawn), and for the material the frame shows the readout
  // (scene::scatter_scale_readout) and the warnings (SssMaterial::model_warnings, a
  // kernel wider than the object).
  double object_mm = 0.0;
  std::string scale_note;
  std::vector<std::string> warnings;
  std::optional<ProfilePlot> plot;  // of the material the frame shows
};

// Timings of the last applied edit, ms; < 0 until known.
struct RefitLatency {
  double fit_ms = -1.0;            // worker: resolve + fit + kernel + plot
  double upload_ms = -1.0;         // render thread: Renderer::set_materials(materials, data)
  double edit_to_frame_ms = -1.0;  // the edit call → the first frame with it presented
  double max_frame_ms = 0.0;       // the longest window frame while the refit ran
  int edits = 0;                   // applied edits measured
};

class MaterialEditor {
 public:
  // separable_taps and single_scattering: the renderer's (RenderOptions), which the fits
  // must match; a change of either on the renderer is followed at the next update().
  MaterialEditor(const scene::Scene& scene, int separable_taps,
                 FitWorker::Compute compute = FitWorker::compute_default,
                 bool single_scattering = renderer::RenderOptions{}.single_scattering);

  // The models offered: all of profiles::kAllModels except mc (2^20 photons per channel
  // take seconds per edit); mc-table, a lookup in the shipped Monte Carlo table, is offered.
  static const std::vector<profiles::Model>& models();
  // Indexes into profiles::presets() and models(); -1 when absent.
  static int preset_index(std::string_view name);
  static int model_index(profiles::Model model);

  // One per material of the scene: those with SSS first (edits()[0] is the one the
  // scripted edits and --soak change), then the others, each in the scene's order.
  std::vector<MaterialEdit>& edits() { return edits_; }
  const std::vector<MaterialEdit>& edits() const { return edits_; }

  // The widgets' calls. Each returns false (error set, nothing submitted) for input that
  // cannot be right; true when a refit was queued.
  bool select_preset(std::size_t edit, int preset);  // fills the coefficient fields
  bool select_model(std::size_t edit, int model);
  // Switches the fields: Coefficients from the current medium; Artist from its total
  // reflectance and reduced mfp; Preset selects the last preset (or skin1).
  bool set_source_kind(std::size_t edit, SourceKind kind);
  // The "enable subsurface" switch. On: the fields are checked and fitted as by apply()
  // (false, error set and the switch left off, when they are not valid). Off: the
  // material is drawn as an opaque PBR surface; its fields stay for the next switch on,
  // and Export writes it with "enabled": false if it had an extras.sss block.
  bool set_enabled(std::size_t edit, bool on);
  // Whether the scene had an SSS material when the editor was made (edits()[0] is one).
  bool had_sss() const { return had_sss_; }
  // The stack (issue 19). add_layer splits layer `at` (the one medium of a material that
  // has no stack, which then becomes a two-layer stack; refused for an artist source) into
  // two identical layers: a finite layer into two halves, when each half stays thicker
  // than its 1/σt'; otherwise a copy goes on top of it, 2·max 1/σt' thick (at least
  // 0.1 mm), and the stack gets that much deeper. Identical layers are the homogeneous
  // medium, so a split of a stack's layer into halves, or of a semi-infinite medium under
  // the default model (mc-table: the stack's base model), keeps the look until a layer is
  // edited. If the new stack is refused, a medium stays one medium. remove_layer drops
  // layer `at`; the last layer left makes the material one medium again, under the
  // default model. move_layer swaps layer `at` with the one above (by = -1) or below
  // (+1). set_layers replaces the stack (`sss-viewer --test-edit layers=FILE.json`). Each
  // applies the result (false: the stack, e.g. a semi-infinite layer moved up, is not
  // valid; its error names the layer and field, and the frame keeps the last valid one).
  bool add_layer(std::size_t edit, std::size_t at);
  bool remove_layer(std::size_t edit, std::size_t at);
  bool move_layer(std::size_t edit, std::size_t at, int by);
  bool set_layers(std::size_t edit, const profiles::LayerStack& stack);
  // Gives layer `at` a preset's coefficients (σa, σs, g; the JSON's {preset, thickness_mm}
  // entry), keeping its thickness. Refused, with the layer as it was, when the preset's η
  // is not the stack's (the interfaces are index-matched), or when the stack it makes is
  // not valid (spectralon absorbs nothing; a layer thinner than the preset's 1/σt'): the
  // error names layers[at] and the field. With `adopt_eta`, a preset whose η differs
  // gives its η to every layer of the stack instead (the interfaces stay index-matched);
  // on any refusal the stack's η is restored with the layer.
  bool set_layer_preset(std::size_t edit, std::size_t at, int preset, bool adopt_eta = false);

  // After the widgets changed the edit's fields (coefficients, artist values, gaussians,
  // scale, albedo): checks and queues a refit. Editing a coefficient of a preset makes
  // the source Coefficients first.
  bool apply(std::size_t edit);

  // Render thread, before render_frame(): uploads the newest finished fit, if any, and
  // returns true if it did. Errors the renderer raises show on the material.
  bool update(renderer::Renderer& r);
  // The window calls this after presenting a frame (frame_ms: its wall-clock time).
  void frame_presented(double frame_ms = 0.0);
  bool busy() const { return worker_.busy() || awaiting_present_; }
  bool fitting() const { return worker_.busy(); }
  // Tests: waits for the worker (not the present), true if it went idle.
  bool wait_idle(std::chrono::milliseconds timeout) const { return worker_.wait_idle(timeout); }

  const RefitLatency& latency() const { return latency_; }
  const std::vector<scene::Material>& applied() const { return applied_; }
  const FitWorker& worker() const { return worker_; }
  // Set by the UI when the user edits the renderer's taps; the next request uses them.
  void set_separable_taps(int taps) { taps_ = taps; }

 private:
  void fill_coefficients(MaterialEdit& e, const profiles::Medium& m);
  static void fill_openpbr(MaterialEdit& e, const profiles::OpenPbrSubsurface& p);
  void fill_layers(MaterialEdit& e, const profiles::LayerStack& stack);
  void fill_notes(MaterialEdit& e) const;  // from applied_[e.index]
  std::optional<SssSpec> spec_from_fields(MaterialEdit& e);
  std::optional<SssSpec> layered_spec(MaterialEdit& e);
  void submit(Clock::time_point edited);

  std::vector<scene::Material> applied_;  // what the renderer draws
  std::shared_ptr<const renderer::MaterialData> applied_data_;  // its fits (null at start)
  std::vector<std::optional<SssSpec>> pending_;  // per material: edited, not applied yet
  std::vector<MaterialEdit> edits_;
  int taps_;
  bool single_scattering_;  // the renderer's, as last seen (update())
  RefitLatency latency_;
  Clock::time_point edited_{};  // of the result awaiting its first present
  bool awaiting_present_ = false;
  bool had_sss_ = false;
  double running_max_frame_ms_ = 0.0;
  FitWorker worker_;  // last: stopped first
};

}  // namespace sss::app
