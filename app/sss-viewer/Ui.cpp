#include "Ui.h"

#include "FrameOutput.h"
#include "InputFiles.h"
#include "PanelWindow.h"
#include "UiColors.h"

#include "profiles/Presets.h"
#include "profiles/Profile.h"
#include "renderer/CameraSetup.h"
#include "renderer/SssTexturePass.h"
#include "image/HeatMap.h"
#include "image/Image.h"
#include "scene/SssLayers.h"

#include <imgui.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>

namespace sss::app {

namespace {

constexpr float kDegrees = 57.29577951f;
constexpr float kPanelWidth = ViewerUi::kPanelWidth;
}  // namespace

ViewerUi::ViewerUi(const scene::Scene& scene, int separable_taps, bool single_scattering)
    : editor_(scene, separable_taps, FitWorker::compute_default, single_scattering),
      lights_(scene.lights),
      environment_(scene.environment),
      environment_on_(scene.environment.has_value()) {
  if (!lights_.empty()) select_light(0);
  if (environment_ && environment_->uniform())
    for (int c = 0; c < 3; ++c) sky_[c] = environment_->colour[c];
  std::size_t sss = 0;
  for (const scene::Material& m : scene.materials) sss += m.sss.enabled ? 1 : 0;
  show_labels_ = sss > 1;
  for (const scene::Instance& inst : scene.instances) {
    if (inst.mesh >= scene.meshes.size()) continue;
    const std::size_t m = scene.meshes[inst.mesh].material;
    if (m < scene.materials.size() && scene.materials[m].sss.enabled)
      labelled_.push_back({scene.meshes[inst.mesh].bounds.transformed(inst.world), m});
  }
}

std::vector<ViewerUi::ScreenLabel> ViewerUi::labels(const scene::Camera& camera, ImVec2 display) const {
  std::vector<ScreenLabel> out;
  if (!(display.x >= 1.0f && display.y >= 1.0f)) return out;
  const std::uint32_t w = std::uint32_t(display.x), h = std::uint32_t(display.y);
  const glm::mat4 clip_from_world = scene::clip_from_view(camera, w, h) * camera.view();
  for (const LabelledObject& o : labelled_) {
    // The box's screen rectangle; a corner behind the camera: no label.
    const std::optional<renderer::ScreenRect> rect = renderer::projected_rect(clip_from_world, o.box, w, h);
    if (!rect || rect->x1 < 0.0 || rect->x0 > display.x || rect->y1 < 0.0 || rect->y0 > display.y)
      continue;
    const ImVec2 lo(float(rect->x0), float(rect->y0)), hi(float(rect->x1), float(rect->y1));
    const MaterialEdit* edit = nullptr;
    for (const MaterialEdit& e : editor_.edits())
      if (e.index == o.material) edit = &e;
    if (edit == nullptr) continue;
    const ImVec2 size = ImGui::CalcTextSize(edit->name.c_str());
    // Under the box's projection; inside the display.
    const float x = std::clamp(0.5f * (lo.x + hi.x) - 0.5f * size.x, 0.0f, std::max(display.x - size.x, 0.0f));
    float y = hi.y + 2.0f;
    // Names wider than the gap between two objects (a small window) step down a line
    // until they clear the labels placed before them.
    const auto overlaps = [&](float top) {
      for (const ScreenLabel& l : out)
        if (x < l.max.x && l.min.x < x + size.x && top < l.max.y && l.min.y < top + size.y)
          return true;
      return false;
    };
    for (int step = 0; step < 8 && overlaps(y); ++step) y += size.y + 2.0f;
    y = std::clamp(y, 0.0f, std::max(display.y - size.y, 0.0f));
    out.push_back({edit->name, ImVec2(x, y), ImVec2(x + size.x, y + size.y)});
  }
  return out;
}

bool valid_script_edit(const std::string& edit) {
  const auto eq = edit.find('=');
  if (eq == std::string::npos) return false;
  const std::string key = edit.substr(0, eq), value = edit.substr(eq + 1);
  if (key == "preset") return profiles::find_preset(value) != nullptr;
  if (key == "layers")
    return std::holds_alternative<profiles::LayerStack>(scene::parse_sss_layers_file(value));
  if (key != "model") return false;
  const auto m = profiles::parse_model(value);
  const auto& offered = MaterialEditor::models();
  return m && std::find(offered.begin(), offered.end(), *m) != offered.end();
}

bool ViewerUi::script_edit(const std::string& edit) {
  if (!editor_.had_sss() || !valid_script_edit(edit)) return false;
  script_ = edit;
  return true;
}

void ViewerUi::draw(renderer::Renderer& r, double frame_ms) {
  smoothed_ms_ = smoothed_ms_ <= 0.0 ? frame_ms : 0.9 * smoothed_ms_ + 0.1 * frame_ms;
  editor_.update(r);  // a finished refit: upload it before this frame renders
  if (!script_.empty() && !editor_.busy()) {  // as if the combo had been clicked
    const auto eq = script_.find('=');
    const std::string key = script_.substr(0, eq), value = script_.substr(eq + 1);
    // valid_script_edit accepted it: the preset or offered model exists.
    if (key == "preset")
      editor_.select_preset(0, MaterialEditor::preset_index(value));
    else if (key == "layers")
      editor_.set_layers(0, std::get<profiles::LayerStack>(scene::parse_sss_layers_file(value)));
    else
      editor_.select_model(0, MaterialEditor::model_index(*profiles::parse_model(value)));
    script_.clear();
  }
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, std::max(display.y - 16.0f, 100.0f)),
                           ImGuiCond_FirstUseEver);
  // A window narrower than three panels opens with this one collapsed to its title: open,
  // it covered all but the right edge of the subject at 640x360. A click on the title
  // opens it.
  ImGui::SetNextWindowCollapsed(starts_collapsed(display.x), ImGuiCond_FirstUseEver);
  if (show_labels_) {
    ImDrawList* back = ImGui::GetBackgroundDrawList();  // over the frame, under the panels
    for (const ScreenLabel& l : labels(r.camera(), display)) {
      back->AddRectFilled(ImVec2(l.min.x - 2.0f, l.min.y - 1.0f), ImVec2(l.max.x + 2.0f, l.max.y + 1.0f),
                          IM_COL32(0, 0, 0, 140), 3.0f);
      back->AddText(l.min, IM_COL32(235, 235, 235, 255), l.text.c_str());
    }
  }
  open_on_title_click(ImGui::Begin("sss-viewer"));
  panel_right_ = ImGui::IsWindowCollapsed() ? 0.0f : ImGui::GetWindowPos().x + ImGui::GetWindowWidth();
  ImGui::PushItemWidth(-100.0f);  // labels keep 100 px on the right
  ImGui::TextWrapped("drag: orbit, shift/middle drag: pan, wheel: zoom, R: reset view");
  draw_sss(r);
  draw_materials(r);
  draw_light(r);
  draw_environment(r);
  draw_stats(r, frame_ms);
  draw_screenshot(r);
  if (!error_.empty()) colored_text_wrapped(kErrorColor, error_.c_str());
  ImGui::PopItemWidth();
  ImGui::End();
}

namespace {
// What a debug view's colours mean, under its combo (nullptr: nothing to say).
const char* debug_view_legend(renderer::DebugView view) {
  switch (view) {
    case renderer::DebugView::KernelRadius:
      return "kernel radius in px on a log2 scale (automatic: 1 px to the largest radius "
             "on screen); magenta < 1 px (the screen kernel undersamples the profile)";
    case renderer::DebugView::Thickness:
      return "mm through the object along light 0 (automatic: 0 to the largest SSS "
             "object's size); grey: no shadow map there";
    case renderer::DebugView::UvStretch:
      return "mm per unit of u (red) and v (green), automatic: 0 to pi x the largest SSS "
               "object's size; grey: no UVs";
    case renderer::DebugView::ProfileId: return "one flat colour per material";
    default: return nullptr;
  }
}
}  // namespace

// The frame's toggles: Fresnel, single scattering, transmission, FXAA, the background.
bool ViewerUi::draw_frame_toggles(renderer::RenderOptions& o) {
  bool changed = false;
  changed |= ImGui::Checkbox("directional Fresnel", &o.fresnel);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("--fresnel: light enters SSS materials x F_t(eta, theta_i) and leaves\n"
                      "in the normalised Fresnel lobe F_t(eta, theta_o)/(c pi); off: all of it\n"
                      "enters and leaves as from a Lambertian surface");
  changed |= ImGui::Checkbox("single scattering", &o.single_scattering);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("--single-scattering: once-scattered light per pixel (closed form, the\n"
                      "material's real g, not blurred); the profiles leave theirs out");
  ImGui::SameLine();
  changed |= ImGui::Checkbox("transmission", &o.transmission);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("--transmission: light through thin parts, thickness from the shadow maps");
  bool fxaa = o.antialias == renderer::Antialias::Fxaa;
  if (ImGui::Checkbox("anti-aliasing", &fxaa)) {
    o.antialias = fxaa ? renderer::Antialias::Fxaa : renderer::Antialias::Off;
    changed = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("--aa fxaa: FXAA over the displayed frame (not in debug views; the EXR\n"
                      "is never filtered)");
  std::array<float, 3> background = o.background.value_or(std::array<float, 3>{});
  if (ImGui::ColorEdit3("background", background.data(), ImGuiColorEditFlags_NoInputs)) {
    o.background = background;
    changed = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("--background R,G,B: the colour behind the geometry (sRGB, opaque)");
  ImGui::SameLine();
  if (ImGui::Checkbox("environment behind", &o.background_environment)) changed = true;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("--background environment: the environment light behind the geometry,\n"
                      "as the camera sees it (where there is one; else the colour)");
  return changed;
}

// The debug view, the labels, the moving scale, and the view's range and legend.
bool ViewerUi::draw_debug_view(const renderer::Renderer& r, renderer::RenderOptions& o) {
  bool changed = false;
  const std::string view_label(renderer::debug_view_name(o.debug_view));
  if (ImGui::BeginCombo("debug view", view_label.c_str())) {
    for (const renderer::DebugView v : renderer::all_debug_views()) {
      const std::string name(renderer::debug_view_name(v));
      if (ImGui::Selectable(name.c_str(), v == o.debug_view) && v != o.debug_view) {
        o.debug_view = v;
        o.debug_range = {0.0f, 0.0f};  // each view starts on its own range
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  ImGui::Checkbox("labels", &show_labels_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("each SSS object's material name under it");
  ImGui::SliderFloat("moving scale", &interactive_scale_, 0.25f, 1.0f, "%.2f");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Render size while the view moves or a slider is dragged\n"
                      "(1 = always full size); full size 0.3 s after the last change");
  // The view's scale (renderer/README.md, "Debug views"): a colour bar with the range the
  // frame uses, and the range to edit.
  if (renderer::debug_view_has_range(o.debug_view)) changed |= draw_debug_range(r, o);
  if (const char* legend = debug_view_legend(o.debug_view); legend != nullptr) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", legend);
    ImGui::PopStyleColor();
  }
  return changed;
}

void ViewerUi::draw_sss(renderer::Renderer& r) {
  if (!ImGui::CollapsingHeader("SSS", ImGuiTreeNodeFlags_DefaultOpen)) return;
  renderer::RenderOptions o = r.options();
  // One label per technique, in SssTechnique's order.
  constexpr const char* kLabels[] = {"off", "screen: separable", "screen: gaussians", "texture space"};
  const auto label = [&](renderer::SssTechnique t) { return kLabels[static_cast<int>(t)]; };
  bool changed = false;
  if (ImGui::BeginCombo("mode", label(o.technique))) {
    for (const renderer::SssTechnique t : renderer::all_techniques())
      if (ImGui::Selectable(label(t), t == o.technique)) {
        changed |= t != o.technique;
        o.technique = t;
      }
    ImGui::EndCombo();
  }
  if (o.technique == renderer::SssTechnique::Texture) changed |= draw_texture_objects(r, o);
  changed |= ImGui::SliderFloat("exposure", &o.exposure, 0.05f, 8.0f, "%.2f",
                                ImGuiSliderFlags_Logarithmic);
  changed |= draw_frame_toggles(o);
  changed |= draw_debug_view(r, o);
  if (!changed) return;
  try {
    r.set_options(o);
    error_.clear();
  } catch (const std::invalid_argument& e) {
    error_ = e.what();
  }
}

bool ViewerUi::draw_debug_range(const renderer::Renderer& r, renderer::RenderOptions& o) {
  const auto [lo, hi] = r.debug_range();
  const bool log_scale = o.debug_view == renderer::DebugView::KernelRadius;
  const std::string unit(renderer::debug_view_unit(o.debug_view));
  // The bar: viridis from lo to hi (uv-stretch draws red and green on 0..1 of the same
  // range, as the legend says), with the ends and the middle labelled.
  const float width = ImGui::GetContentRegionAvail().x, height = 10.0f;
  const ImVec2 at = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  constexpr int kSteps = 48;
  for (int k = 0; k < kSteps; ++k) {
    const double t = (k + 0.5) / kSteps;
    image::Rgb c = image::viridis(t);
    if (o.debug_view == renderer::DebugView::UvStretch) c = {float(t), float(t), 0.0f};
    const float x0 = at.x + width * float(k) / kSteps, x1 = at.x + width * float(k + 1) / kSteps;
    draw->AddRectFilled(ImVec2(x0, at.y), ImVec2(x1, at.y + height),
                        IM_COL32(int(255 * c[0]), int(255 * c[1]), int(255 * c[2]), 255));
  }
  ImGui::Dummy(ImVec2(width, height));
  const double mid = log_scale ? std::sqrt(double(lo) * double(hi)) : 0.5 * (double(lo) + double(hi));
  char text[3][32];
  std::snprintf(text[0], sizeof text[0], "%.3g", double(lo));
  std::snprintf(text[1], sizeof text[1], "%.3g", mid);
  std::snprintf(text[2], sizeof text[2], "%.3g %s", double(hi), unit.c_str());
  const float y = ImGui::GetCursorPosY();
  ImGui::TextUnformatted(text[0]);
  ImGui::SameLine(0.5f * width - 0.5f * ImGui::CalcTextSize(text[1]).x);
  ImGui::SetCursorPosY(y);
  ImGui::TextUnformatted(text[1]);
  ImGui::SameLine(width - ImGui::CalcTextSize(text[2]).x);
  ImGui::SetCursorPosY(y);
  ImGui::TextUnformatted(text[2]);

  bool automatic = o.debug_range == std::array<float, 2>{0.0f, 0.0f};
  bool changed = false;
  if (ImGui::Checkbox("automatic range", &automatic)) {
    o.debug_range = automatic ? std::array<float, 2>{0.0f, 0.0f} : std::array<float, 2>{lo, hi};
    changed = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("on: the range follows the camera and the materials (--debug-range sets it)");
  if (!automatic) {
    float ends[2] = {o.debug_range[0], o.debug_range[1]};
    const float speed = 0.005f * std::max(ends[1] - ends[0], 1e-3f);
    if (ImGui::DragFloatRange2("range", &ends[0], &ends[1], speed, log_scale ? 0.01f : 0.0f,
                               1e6f, "%.3g", "%.3g", ImGuiSliderFlags_AlwaysClamp)) {
      const std::array<float, 2> edited{ends[0], ends[1]};
      if (renderer::debug_range_error(o.debug_view, edited).empty()) {
        o.debug_range = edited;
        changed = true;
      }
    }
  }
  return changed;
}

bool ViewerUi::draw_texture_objects(const renderer::Renderer& r, renderer::RenderOptions& o) {
  const renderer::SssTexturePass* texture = r.texture_pass();
  if (texture == nullptr) return false;
  bool changed = false;
  static constexpr std::uint32_t kSizes[] = {256, 512, 1024, 2048};
  static const char* kSizeNames[] = {"256", "512", "1024", "2048"};
  static const char* kUpdates[] = {"every frame", "on change"};
  ImGui::TextDisabled("per object: irradiance texture, recompute");
  for (std::size_t i = 0; i < texture->objects().size(); ++i) {
    const renderer::SssTexturePass::Object& obj = texture->objects()[i];
    renderer::TextureObjectOptions t = obj.options;
    ImGui::PushID(static_cast<int>(i));  // names repeat (a node's primitives)
    int size = 0;
    while (size < 3 && kSizes[size] < t.size) ++size;
    int update = t.update == renderer::TextureUpdate::EveryFrame ? 0 : 1;
    ImGui::TextUnformatted(t.name.c_str());
    ImGui::SameLine();
    ImGui::TextDisabled("(%llu updates)", static_cast<unsigned long long>(obj.updates));
    ImGui::PushItemWidth(ImGui::GetContentRegionAvail().x * 0.45f);
    const bool size_edited = ImGui::Combo("##size", &size, kSizeNames, 4);
    ImGui::SameLine();
    const bool update_edited = ImGui::Combo("##update", &update, kUpdates, 2);
    ImGui::PopItemWidth();
    ImGui::PopID();
    if (!size_edited && !update_edited) continue;
    if (size_edited) t.size = kSizes[size];  // a size from the command line stays otherwise
    t.update = update == 0 ? renderer::TextureUpdate::EveryFrame : renderer::TextureUpdate::OnChange;
    auto it = std::find_if(o.texture_objects.begin(), o.texture_objects.end(),
                           [&](const renderer::TextureObjectOptions& x) { return x.name == t.name; });
    if (it == o.texture_objects.end())
      o.texture_objects.push_back(t);
    else
      *it = t;
    changed = true;
  }
  for (const std::string& w : texture->warnings()) colored_text_wrapped(kErrorColor, w.c_str());
  return changed;
}

void ViewerUi::select_light(std::size_t i) {
  light_ = int(i);
  const scene::Light& l = lights_[i];
  const glm::vec3 to_light = -l.direction();
  elevation_deg_ = std::asin(std::clamp(to_light.y, -1.0f, 1.0f)) * kDegrees;
  azimuth_deg_ = std::atan2(to_light.x, to_light.z) * kDegrees;
  intensity_ = l.intensity;
  for (int c = 0; c < 3; ++c) light_color_[c] = l.color[c];
}

bool ViewerUi::set_light(renderer::Renderer& r, std::size_t i, float azimuth_deg,
                         float elevation_deg, float intensity, const float color[3]) {
  if (i >= lights_.size()) return false;
  std::vector<scene::Light> next = lights_;
  scene::Light& l = next[i];
  if (l.type != scene::LightType::Point) {
    const float az = azimuth_deg / kDegrees, el = elevation_deg / kDegrees;
    const glm::vec3 to_light(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    const glm::vec3 pos = l.position();
    const glm::vec3 up = std::fabs(to_light.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    l.world = scene::look_at_world(pos, pos - to_light, up);  // local -Z travels away from the light
  }
  l.intensity = std::max(intensity, 0.0f);
  for (int c = 0; c < 3; ++c) l.color[c] = std::max(color[c], 0.0f);
  try {
    r.set_lights(next);
  } catch (const std::invalid_argument& e) {
    error_ = e.what();
    return false;
  }
  lights_ = std::move(next);
  error_.clear();
  return true;
}

void ViewerUi::draw_light(renderer::Renderer& r) {
  if (lights_.empty() || !ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) return;
  auto name = [this](std::size_t i) {
    const scene::Light& l = lights_[i];
    return l.name.empty() ? "light " + std::to_string(i) : l.name;
  };
  auto label = [&](std::size_t i) {
    const scene::Light& l = lights_[i];
    const char* type = l.type == scene::LightType::Directional ? "directional"
                       : l.type == scene::LightType::Spot      ? "spot"
                                                                : "point";
    return name(i) + " (" + type + ")";
  };
  // The closed combo shows the name alone ("key (behind) (directional)" did not fit and
  // was cut); the list and the tooltip say the type.
  if (ImGui::BeginCombo("light", name(std::size_t(light_)).c_str())) {
    for (std::size_t i = 0; i < lights_.size(); ++i)
      if (ImGui::Selectable(label(i).c_str(), int(i) == light_)) select_light(i);
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", label(std::size_t(light_)).c_str());
  const bool point = lights_[std::size_t(light_)].type == scene::LightType::Point;
  ImGui::BeginDisabled(point);  // a point light has no direction
  bool changed = ImGui::SliderFloat("azimuth", &azimuth_deg_, -180.0f, 180.0f, "%.0f deg");
  changed |= ImGui::SliderFloat("elevation", &elevation_deg_, -89.0f, 89.0f, "%.0f deg");
  ImGui::EndDisabled();
  changed |= ImGui::SliderFloat("intensity", &intensity_, 0.0f, 20.0f, "%.3g",
                                ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::ColorEdit3("colour##light", light_color_, ImGuiColorEditFlags_Float);
  if (changed) set_light(r, std::size_t(light_), azimuth_deg_, elevation_deg_, intensity_, light_color_);
}

void ViewerUi::draw_environment(renderer::Renderer& r) {
  if (!ImGui::CollapsingHeader("Environment")) return;
  const bool image = environment_ && !environment_->uniform();
  bool changed = ImGui::Checkbox("environment light", &environment_on_);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("--environment: light from every direction; its diffuse part scattered like\n"
                      "the other lights (spherical harmonics), its specular from a prefiltered map\n"
                      "(split sum); the diffuse part less what the scene blocks (sky occlusion)");
  ImGui::BeginDisabled(!environment_on_);
  renderer::RenderOptions options = r.options();
  if (ImGui::Checkbox("sky occlusion", &options.sky_occlusion)) r.set_options(options);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("--sky-occlusion: take away the sky that the scene blocks, per vertex\n"
                      "(ray-cast once when first needed); off: every surface sees the whole sky");
  if (image) {
    ImGui::TextWrapped("image: %s", environment_->source.c_str());
  } else {
    changed |= ImGui::ColorEdit3("sky##environment", sky_, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("--environment R,G,B: a uniform sky's linear radiance");
  }
  changed |= ImGui::SliderFloat("scale##environment", &environment_scale_, 0.0f, 10.0f, "%.3g",
                                ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("multiplies the radiance (after --environment-intensity)");
  ImGui::EndDisabled();
  if (!changed) return;
  std::optional<scene::Environment> next;
  if (environment_on_) {
    const float k = std::max(environment_scale_, 0.0f);
    if (image) {
      next = *environment_;
      next->scale(k);
    } else {
      next = scene::uniform_environment(glm::max(glm::vec3(sky_[0], sky_[1], sky_[2]), glm::vec3(0.0f)), k);
    }
  }
  r.set_environment(next);
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
  const RefitLatency& l = editor_.latency();
  if (l.edits > 0) {
    ImGui::Text("refit (last edit, %d so far)", l.edits);
    ImGui::Text("  %-14s %7.2f ms", "fit (worker)", l.fit_ms);
    ImGui::Text("  %-14s %7.2f ms", "upload", l.upload_ms);
    ImGui::Text("  %-14s %7.2f ms", "edit->frame", l.edit_to_frame_ms);
    ImGui::Text("  %-14s %7.2f ms", "max frame", l.max_frame_ms);
  } else if (editor_.fitting()) {
    ImGui::TextUnformatted("refit: fitting...");
  }
}

void ViewerUi::print_stats(std::FILE* out) const {
  const RefitLatency& l = editor_.latency();
  if (l.edits == 0) return;
  std::fprintf(out, "%-16s %10.3f\n", "refit fit", l.fit_ms);
  std::fprintf(out, "%-16s %10.3f\n", "refit upload", l.upload_ms);
  std::fprintf(out, "%-16s %10.3f\n", "edit->frame", l.edit_to_frame_ms);
  std::fprintf(out, "%-16s %10.3f\n", "refit max frame", l.max_frame_ms);
}

std::optional<std::string> ViewerUi::screenshot_refusal(const std::string& path) const {
  return refuse_input_overwrite(path, protected_);
}

void ViewerUi::draw_screenshot(const renderer::Renderer& r) {
  if (!ImGui::CollapsingHeader("Screenshot", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::InputText("file", shot_name_, sizeof shot_name_);
  const bool png = ImGui::Button("Save PNG");
  ImGui::SameLine();
  const bool exr = ImGui::Button("Save EXR");
  if (png || exr) {
    const std::string path = std::string(shot_name_) + (png ? ".png" : ".exr");
    if (auto refused = screenshot_refusal(path)) {
      shot_message_ = *refused;
    } else {
      try {
        write_frame(r, path);
        shot_message_ = "saved " + path;
      } catch (const std::exception& e) {
        shot_message_ = e.what();
      }
    }
  }
  if (!shot_message_.empty()) ImGui::TextUnformatted(shot_message_.c_str());
}

}  // namespace sss::app
