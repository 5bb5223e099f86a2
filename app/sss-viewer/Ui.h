// The viewer's ImGui panels: SSS mode, a material editor per SSS material (preset, model,
// σa/σs/g/η or artist colour + mfp, with a plot of the profile and its fit), every light,
// per-pass and refit stats, and screenshots. Every change goes through the Renderer's
// live calls (set_options, set_materials, set_lights) between frames; material refits run
// on a worker thread (MaterialEditor, FitWorker) and only their upload happens here.
#pragma once

#include "MaterialEditor.h"

#include "renderer/Renderer.h"
#include "scene/Scene.h"

#include <imgui.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sss::app {

// Whether `edit` is a scripted edit script_edit accepts ("preset=NAME" with a known
// preset, "model=NAME" with an offered model, "layers=FILE.json" with a valid stack file):
// checked before a window opens.
bool valid_script_edit(const std::string& edit);

class ViewerUi {
 public:
  static constexpr float kPanelWidth = 320.0f;  // <= 35% of a 960-pixel-wide window
  // The panel opens collapsed to its title in a window narrower than three panels (640x360:
  // open, it hid all but the edge of the subject); a click on the title opens it.
  static bool starts_collapsed(float display_width) { return display_width < 3.0f * kPanelWidth; }

  explicit ViewerUi(const scene::Scene& scene, int separable_taps = 17,
                    bool single_scattering = renderer::RenderOptions{}.single_scattering);

  // Builds the panels for this ImGui frame (between ImGui::NewFrame and ImGui::Render)
  // and applies what changed, including a finished refit. frame_ms: the wall-clock time
  // of the last window frame.
  void draw(renderer::Renderer& r, double frame_ms);
  // After each presented frame: closes the refit latency (edit → first frame with it).
  void frame_presented(double frame_ms) { editor_.frame_presented(frame_ms); }
  // A refit is running or waiting to be presented.
  bool busy() const { return editor_.busy(); }
  // Scripted edit (sss-viewer --test-edit): "preset=NAME", "model=NAME" or
  // "layers=FILE.json" (MaterialEditor::set_layers) on the first
  // SSS material, made by the first draw() with no refit running (the start-up one
  // done), through the widgets' own calls. False if the
  // text names nothing.
  bool script_edit(const std::string& edit);
  // The refit timings, for --stats.
  void print_stats(std::FILE* out) const;

  MaterialEditor& editor() { return editor_; }
  // The right edge of the open panel in display pixels after the last draw(); 0 while it
  // is collapsed to its title (the window frames the subject beside it, OrbitCamera).
  float panel_right() const { return panel_right_; }

  // Object labels (issue 20: "label the spheres of builtin:materials"): the name of each
  // SSS object's material, centred under its projected box, drawn over the frame and under
  // the panels. On by default when the scene has more than one SSS material; the SSS
  // panel's "labels" switch. labels() is what draw() draws, for a frame of `display`
  // pixels seen by `camera`; objects behind the camera or off screen get none.
  struct ScreenLabel {
    std::string text;
    ImVec2 min, max;  // the text's rectangle, display pixels
  };
  std::vector<ScreenLabel> labels(const scene::Camera& camera, ImVec2 display) const;
  bool show_labels() const { return show_labels_; }

  // The scene's own files (InputFiles.h): the Screenshot panel refuses to write over them.
  void set_protected_files(std::vector<std::filesystem::path> files) { protected_ = std::move(files); }
  // What the Screenshot panel would write to `path`: nullopt to go ahead, or why not.
  std::optional<std::string> screenshot_refusal(const std::string& path) const;

  // The window renders at this fraction of its size while the view moves or a widget is
  // dragged (1: always full size); the SSS panel's "moving scale" slider sets it.
  float interactive_scale() const { return interactive_scale_; }
  void set_interactive_scale(float s) { interactive_scale_ = s; }

  // The light panel's logic (the widgets call it): light `i` shines from azimuth/elevation
  // (degrees; the light travels towards the origin's side), with intensity and colour.
  bool set_light(renderer::Renderer& r, std::size_t i, float azimuth_deg, float elevation_deg,
                 float intensity, const float color[3]);
  const std::vector<scene::Light>& lights() const { return lights_; }

 private:
  void draw_sss(renderer::Renderer& r);
  // Texture mode: each object's texture size and update policy; true when o changed.
  bool draw_texture_objects(const renderer::Renderer& r, renderer::RenderOptions& o);
  // draw_sss's parts, each true if o changed: the frame's toggles (Fresnel, single
  // scattering, transmission, FXAA, background); the debug view with its range and legend.
  bool draw_frame_toggles(renderer::RenderOptions& o);
  bool draw_debug_view(const renderer::Renderer& r, renderer::RenderOptions& o);
  // The debug view's colour bar, its range, and the range's editor; true if o changed.
  bool draw_debug_range(const renderer::Renderer& r, renderer::RenderOptions& o);
  void draw_materials(renderer::Renderer& r);
  void draw_material(MaterialEdit& e, std::size_t i);
  // draw_material's parts: the preset, model and kind of source; the medium's fields
  // (true: refit); the errors, notes and plot. `layered`: e had layers as the frame began.
  void draw_source(MaterialEdit& e, std::size_t i, bool layered);
  bool draw_medium(MaterialEdit& e, std::size_t i, bool layered);
  void draw_material_status(MaterialEdit& e);
  // A stack's rows (per layer: its coefficients, thickness, split / up / down / remove) and
  // its η; true when a field's edit ended (the caller applies).
  bool draw_layers(MaterialEdit& e, std::size_t i);
  void draw_light(renderer::Renderer& r);
  // The environment light: on/off, a uniform sky's colour, or the image's name; a scale.
  void draw_environment(renderer::Renderer& r);
  void draw_stats(const renderer::Renderer& r, double frame_ms);
  void draw_screenshot(const renderer::Renderer& r);
  void select_light(std::size_t i);

  MaterialEditor editor_;
  struct LabelledObject {
    scene::Bounds box;  // world units
    std::size_t material = 0;
  };
  std::vector<LabelledObject> labelled_;  // the SSS instances
  bool show_labels_ = false;
  float panel_right_ = 0.0f;
  std::vector<scene::Light> lights_;
  int light_ = 0;  // the light the panel edits
  float azimuth_deg_ = 0.0f, elevation_deg_ = 0.0f, intensity_ = 1.0f;
  float light_color_[3] = {1.0f, 1.0f, 1.0f};
  // The environment as loaded (--environment, its intensity applied), and the panel's edits.
  std::optional<scene::Environment> environment_;
  bool environment_on_ = false;
  float sky_[3] = {0.3f, 0.3f, 0.3f};  // a uniform sky's linear radiance
  float environment_scale_ = 1.0f;
  bool plot_error_ = true;
  float interactive_scale_ = 0.5f;  // the plot shows the fit's relative error below
  std::string script_;
  double smoothed_ms_ = 0.0;
  char shot_name_[256] = "sss-viewer";
  std::string shot_message_;
  std::vector<std::filesystem::path> protected_;
  std::string error_;
};

}  // namespace sss::app
