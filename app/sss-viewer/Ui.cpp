#include "Ui.h"

#include "profiles/Presets.h"
#include "profiles/Profile.h"
#include "renderer/image/Image.h"

#include <imgui.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <stdexcept>

namespace sss::app {

namespace {

constexpr float kDegrees = 57.29577951f;

std::string preset_label(int i) {
  return i < 0 ? std::string("(scene's own)") : std::string(profiles::presets()[std::size_t(i)].name);
}

}  // namespace

ViewerUi::ViewerUi(const scene::Scene& scene) : materials_(scene.materials), lights_(scene.lights) {
  for (std::size_t i = 0; i < profiles::kAllModels.size(); ++i)
    if (profiles::kAllModels[i] != profiles::Model::MonteCarlo) models_.push_back(int(i));
  for (std::size_t i = 0; i < materials_.size(); ++i) {
    const scene::SssMaterial& s = materials_[i].sss;
    if (!s.enabled) continue;
    MaterialEdit e;
    e.index = i;
    if (const auto* p = std::get_if<scene::PresetSource>(&s.source)) {
      const auto all = profiles::presets();
      for (std::size_t k = 0; k < all.size(); ++k)
        if (all[k].name == p->name) e.preset = int(k);
    }
    for (std::size_t m = 0; m < models_.size(); ++m)
      if (profiles::kAllModels[std::size_t(models_[m])] == s.model) e.model = int(m);
    e.gaussians = s.gaussians;
    e.scale = float(s.scale);
    e.albedo = s.albedo_mode == scene::AlbedoMode::PrePost ? 1 : 0;
    edits_.push_back(e);
  }
  if (!lights_.empty()) {
    const glm::vec3 to_light = -lights_[0].direction();
    elevation_deg_ = std::asin(std::clamp(to_light.y, -1.0f, 1.0f)) * kDegrees;
    azimuth_deg_ = std::atan2(to_light.x, to_light.z) * kDegrees;
    intensity_ = lights_[0].intensity;
  }
}

void ViewerUi::draw(renderer::Renderer& r, double frame_ms) {
  smoothed_ms_ = smoothed_ms_ <= 0.0 ? frame_ms : 0.9 * smoothed_ms_ + 0.1 * frame_ms;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("sss-viewer");
  ImGui::TextWrapped("drag: orbit, shift/middle drag: pan, wheel: zoom, R: reset view");
  draw_sss(r);
  draw_materials(r);
  draw_light(r);
  draw_stats(r, frame_ms);
  draw_screenshot(r);
  if (!error_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_.c_str());
  ImGui::End();
}

void ViewerUi::draw_sss(renderer::Renderer& r) {
  if (!ImGui::CollapsingHeader("SSS", ImGuiTreeNodeFlags_DefaultOpen)) return;
  renderer::RenderOptions o = r.options();
  int mode = o.sss == renderer::SssMode::Off ? 0 : (o.kind == renderer::SssKind::Separable ? 1 : 2);
  const char* modes[] = {"off", "separable", "gaussians"};
  bool changed = ImGui::Combo("mode", &mode, modes, 3);
  changed |= ImGui::SliderFloat("exposure", &o.exposure, 0.05f, 8.0f, "%.2f",
                                ImGuiSliderFlags_Logarithmic);
  if (!changed) return;
  o.sss = mode == 0 ? renderer::SssMode::Off : renderer::SssMode::Screen;
  if (mode != 0) o.kind = mode == 1 ? renderer::SssKind::Separable : renderer::SssKind::Gaussians;
  try {
    r.set_options(o);
    error_.clear();
  } catch (const std::invalid_argument& e) {
    error_ = e.what();
  }
}

void ViewerUi::draw_materials(renderer::Renderer& r) {
  if (edits_.empty() || !ImGui::CollapsingHeader("Materials", ImGuiTreeNodeFlags_DefaultOpen))
    return;
  const auto all = profiles::presets();
  for (MaterialEdit& e : edits_) {
    ImGui::PushID(int(e.index));
    const std::string& name = materials_[e.index].name;
    if (ImGui::TreeNodeEx("material", ImGuiTreeNodeFlags_DefaultOpen, "%s",
                          name.empty() ? "(unnamed)" : name.c_str())) {
      bool changed = false;
      if (ImGui::BeginCombo("preset", preset_label(e.preset).c_str())) {
        for (int k = 0; k < int(all.size()); ++k)
          if (ImGui::Selectable(preset_label(k).c_str(), k == e.preset)) {
            changed |= k != e.preset;
            e.preset = k;
          }
        ImGui::EndCombo();
      }
      const std::string model_label(
          profiles::model_name(profiles::kAllModels[std::size_t(models_[std::size_t(e.model)])]));
      if (ImGui::BeginCombo("model", model_label.c_str())) {
        for (int m = 0; m < int(models_.size()); ++m) {
          const std::string label(profiles::model_name(profiles::kAllModels[std::size_t(models_[std::size_t(m)])]));
          if (ImGui::Selectable(label.c_str(), m == e.model)) {
            changed |= m != e.model;
            e.model = m;
          }
        }
        ImGui::EndCombo();
      }
      changed |= ImGui::SliderInt("gaussians", &e.gaussians, scene::kMinGaussians,
                                  scene::kMaxGaussians);
      changed |= ImGui::SliderFloat("scale", &e.scale, 0.05f, 20.0f, "%.2f",
                                    ImGuiSliderFlags_Logarithmic);
      const char* albedo[] = {"post-scatter", "pre-post"};
      changed |= ImGui::Combo("albedo", &e.albedo, albedo, 2);
      // Refit when a slider is released, not on every drag step (pbd takes ~0.5 s).
      e.pending |= changed;
      if (e.pending && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        e.pending = false;
        apply_material(r, e);
      }
      if (e.refit_ms >= 0.0) ImGui::Text("refit + upload: %.1f ms", e.refit_ms);
      if (!e.error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", e.error.c_str());
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

void ViewerUi::apply_material(renderer::Renderer& r, MaterialEdit& e) {
  scene::Material& m = materials_[e.index];
  scene::SssSource source = m.sss.source;
  if (e.preset >= 0)
    source = scene::PresetSource{std::string(profiles::presets()[std::size_t(e.preset)].name)};
  auto made = scene::make_sss_material(
      source, profiles::kAllModels[std::size_t(models_[std::size_t(e.model)])], e.gaussians,
      double(e.scale), e.albedo == 1 ? scene::AlbedoMode::PrePost : scene::AlbedoMode::PostScatter);
  if (auto* err = std::get_if<FieldError>(&made)) {
    e.error = err->what();
    return;
  }
  std::vector<scene::Material> next = materials_;
  next[e.index].sss = std::get<scene::SssMaterial>(made);
  const auto start = std::chrono::steady_clock::now();
  try {
    r.set_materials(next);
  } catch (const std::exception& ex) {
    e.error = ex.what();
    return;
  }
  e.refit_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  e.error.clear();
  materials_ = std::move(next);
}

void ViewerUi::draw_light(renderer::Renderer& r) {
  if (lights_.empty() || !ImGui::CollapsingHeader("Light", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::Text("%s", lights_[0].name.empty() ? "light 0" : lights_[0].name.c_str());
  bool changed = ImGui::SliderFloat("azimuth", &azimuth_deg_, -180.0f, 180.0f, "%.0f deg");
  changed |= ImGui::SliderFloat("elevation", &elevation_deg_, -89.0f, 89.0f, "%.0f deg");
  changed |= ImGui::SliderFloat("intensity", &intensity_, 0.0f, 20.0f, "%.2f");
  if (changed) apply_light(r);
}

void ViewerUi::apply_light(renderer::Renderer& r) {
  scene::Light& l = lights_[0];
  const float az = azimuth_deg_ / kDegrees, el = elevation_deg_ / kDegrees;
  const glm::vec3 to_light(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
  const glm::vec3 pos = l.position();
  const glm::vec3 up = std::fabs(to_light.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  l.world = scene::look_at_world(pos, pos - to_light, up);  // local -Z travels away from the light
  l.intensity = std::max(intensity_, 0.0f);
  try {
    r.set_lights(lights_);
    error_.clear();
  } catch (const std::invalid_argument& e) {
    error_ = e.what();
  }
}

void ViewerUi::draw_stats(const renderer::Renderer& r, double frame_ms) {
  if (!ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const renderer::FrameStats& s = r.stats();
  ImGui::Text("%ux%u  %.1f fps  frame %.1f ms (last %.1f)", r.options().width,
              r.options().height, smoothed_ms_ > 0.0 ? 1000.0 / smoothed_ms_ : 0.0, smoothed_ms_,
              frame_ms);
  for (const vk::PassTime& p : s.passes) ImGui::Text("  %-14s %7.2f ms", p.name.c_str(), p.ms);
  ImGui::Text("  %-14s %7.2f ms", "gpu total", s.gpu_ms);
  ImGui::Text("  %-14s %7.2f ms", "renderer cpu", s.cpu_ms);
}

void ViewerUi::draw_screenshot(const renderer::Renderer& r) {
  if (!ImGui::CollapsingHeader("Screenshot", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::InputText("file", shot_name_, sizeof shot_name_);
  const bool png = ImGui::Button("Save PNG");
  ImGui::SameLine();
  const bool exr = ImGui::Button("Save EXR");
  if (png || exr) {
    const std::string path = std::string(shot_name_) + (png ? ".png" : ".exr");
    try {
      if (png)
        image::write_png(path, r.read_display());
      else
        image::write_exr(path, r.read_hdr());
      shot_message_ = "saved " + path;
    } catch (const std::exception& e) {
      shot_message_ = e.what();
    }
  }
  if (!shot_message_.empty()) ImGui::TextUnformatted(shot_message_.c_str());
}

}  // namespace sss::app
