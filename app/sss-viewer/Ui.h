// The viewer's ImGui panels: SSS mode, a material editor per SSS material, the key
// light, per-pass stats and screenshots. Every change goes through the Renderer's live
// calls (set_options, set_materials, set_lights) between frames.
#pragma once

#include "renderer/Renderer.h"
#include "renderer/scene/Scene.h"

#include <string>
#include <vector>

namespace sss::app {

class ViewerUi {
 public:
  explicit ViewerUi(const scene::Scene& scene);

  // Builds the panels for this ImGui frame (between ImGui::NewFrame and ImGui::Render)
  // and applies what changed. frame_ms: the wall-clock time of the last window frame.
  void draw(renderer::Renderer& r, double frame_ms);

 private:
  struct MaterialEdit {
    std::size_t index = 0;  // into materials_
    int preset = -1;        // into profiles::presets(); -1: the material's own source
    int model = 0;          // into models_
    int gaussians = 6;
    float scale = 1.0f;
    int albedo = 0;  // 0 post-scatter, 1 pre-post
    bool pending = false;  // changed, applied when the mouse is released
    double refit_ms = -1.0;
    std::string error;
  };

  void draw_sss(renderer::Renderer& r);
  void draw_materials(renderer::Renderer& r);
  void draw_light(renderer::Renderer& r);
  void draw_stats(const renderer::Renderer& r, double frame_ms);
  void draw_screenshot(const renderer::Renderer& r);
  void apply_material(renderer::Renderer& r, MaterialEdit& edit);
  void apply_light(renderer::Renderer& r);

  std::vector<scene::Material> materials_;
  std::vector<scene::Light> lights_;
  std::vector<MaterialEdit> edits_;
  std::vector<int> models_;  // profiles::kAllModels indices offered (all but mc)
  float azimuth_deg_ = 0.0f, elevation_deg_ = 0.0f, intensity_ = 1.0f;
  double smoothed_ms_ = 0.0;
  char shot_name_[256] = "sss-viewer";
  std::string shot_message_;
  std::string error_;
};

}  // namespace sss::app
