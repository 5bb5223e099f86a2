#include "Ui.h"

#include "FrameOutput.h"
#include "InputFiles.h"
#include "PanelWindow.h"

#include "profiles/Presets.h"
#include "profiles/Profile.h"
#include "renderer/CameraSetup.h"
#include "renderer/SssTexturePass.h"
#include "renderer/image/HeatMap.h"
#include "renderer/image/Image.h"
#include "renderer/scene/SssLayers.h"

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
const ImVec4 kErrorColor(1.0f, 0.4f, 0.4f, 1.0f);
const ImVec4 kWarningColor(1.0f, 0.85f, 0.3f, 1.0f);
const ImU32 kChannelColor[3] = {IM_COL32(255, 90, 80, 255), IM_COL32(90, 220, 90, 255),
                                IM_COL32(100, 140, 255, 255)};

std::string preset_label(int i) {
  return i < 0 ? std::string("(custom)") : std::string(profiles::presets()[std::size_t(i)].name);
}

std::string model_label(int m) {
  return std::string(profiles::model_name(MaterialEditor::models()[std::size_t(m)]));
}

// "1e-3", "0.01", "0.1", "1", "10", "100", "1e3": a decade's tick label.
std::string decade_label(int e) {
  if (e >= -2 && e <= 2) {
    static const char* text[] = {"0.01", "0.1", "1", "10", "100"};
    return text[e + 2];
  }
  return "1e" + std::to_string(e);
}

// One log-log panel of the plot: x over [10^xr.lo, 10^xr.hi], y over [10^yr.lo, 10^yr.hi].
struct LogAxes {
  ImVec2 p0, p1;  // the plot area, screen pixels
  LogRange x, y;
  ImVec2 map(double xv, double yv) const {
    const double u = (std::log10(xv) - x.lo) / (x.hi - x.lo);
    const double v = (std::log10(std::max(yv, 1e-300)) - y.lo) / (y.hi - y.lo);
    return ImVec2(p0.x + float(u) * (p1.x - p0.x),
                  p1.y - float(std::clamp(v, -0.05, 1.05)) * (p1.y - p0.y));
  }
};

// Frame, decade grid and labels (y labels inside the left margin, x labels below).
void draw_axes(ImDrawList* dl, const LogAxes& a, bool x_labels, const char* y_title) {
  const ImU32 grid = IM_COL32(255, 255, 255, 40), text = IM_COL32(200, 200, 200, 255);
  dl->AddRect(a.p0, a.p1, IM_COL32(255, 255, 255, 90));
  // A label every ystep decades, so that labels (13 px) never touch.
  const float decade_px = (a.p1.y - a.p0.y) / float(a.y.hi - a.y.lo);
  const int ystep = std::max(1, int(std::ceil(15.0f / decade_px)));
  for (int e = a.y.lo; e <= a.y.hi; ++e) {
    const float y = a.map(std::pow(10.0, a.x.lo), std::pow(10.0, e)).y;
    dl->AddLine(ImVec2(a.p0.x, y), ImVec2(a.p1.x, y), grid);
    if ((a.y.hi - e) % ystep == 0) {
      const std::string s = decade_label(e);
      const float ty = std::clamp(y - 7.0f, a.p0.y - 2.0f, a.p1.y - 12.0f);
      dl->AddText(ImVec2(a.p0.x - ImGui::CalcTextSize(s.c_str()).x - 3, ty), text, s.c_str());
    }
  }
  for (int e = a.x.lo; e <= a.x.hi; ++e) {
    const float x = a.map(std::pow(10.0, e), std::pow(10.0, a.y.lo)).x;
    dl->AddLine(ImVec2(x, a.p0.y), ImVec2(x, a.p1.y), grid);
    if (x_labels) {
      const std::string s = decade_label(e);
      const float w = ImGui::CalcTextSize(s.c_str()).x;
      dl->AddText(ImVec2(std::min(x - w * 0.5f, a.p1.x - w), a.p1.y + 1), text, s.c_str());
    }
  }
  dl->AddText(ImVec2(a.p1.x - ImGui::CalcTextSize(y_title).x - 3, a.p0.y + 1), text, y_title);
}

// One curve per channel; dashed draws every other segment.
// pattern 0: solid; k > 1: one segment in k drawn (2 dashed, 3 dotted).
void draw_curves(ImDrawList* dl, const LogAxes& a, const std::vector<double>& r,
                 const std::vector<Rgb>& v, int pattern, float thickness) {
  for (int c = 0; c < 3; ++c)
    for (std::size_t i = 1; i < r.size() && i < v.size(); ++i) {
      if (pattern > 1 && i % std::size_t(pattern) != 1) continue;
      if (!(v[i - 1][c] > 0.0) || !(v[i][c] > 0.0)) continue;
      dl->AddLine(a.map(r[i - 1], v[i - 1][c]), a.map(r[i], v[i][c]), kChannelColor[c], thickness);
    }
}

// r·R(r) of the model (solid) and the fit (dashed), and the relative error, log-log.
void draw_profile_plot(const ProfilePlot& p, bool with_error) {
  const float width = ImGui::GetContentRegionAvail().x;
  const float margin = 34.0f, top_h = 110.0f, err_h = with_error ? 56.0f : 0.0f, label_h = 14.0f;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float total_h = top_h + (with_error ? err_h + 6.0f : 0.0f) + label_h;
  ImGui::Dummy(ImVec2(width, total_h));
  ImDrawList* dl = ImGui::GetWindowDrawList();
  std::vector<double> all;
  for (const Rgb& v : p.model_rR) all.insert(all.end(), v.begin(), v.end());
  for (const Rgb& v : p.model_rT) all.insert(all.end(), v.begin(), v.end());
  LogAxes top;
  top.p0 = ImVec2(origin.x + margin, origin.y);
  top.p1 = ImVec2(origin.x + width - 4, origin.y + top_h);
  top.x.lo = int(std::floor(std::log10(p.r_mm.front())));
  top.x.hi = int(std::ceil(std::log10(p.r_mm.back())));
  top.y = log_range(all, 5);
  dl->PushClipRect(ImVec2(origin.x, origin.y - 8), ImVec2(origin.x + width, origin.y + total_h), true);
  draw_axes(dl, top, !with_error, p.model_rT.empty() ? "r R(r) 1/mm" : "r R(r), r T(r) 1/mm");
  dl->PushClipRect(top.p0, top.p1, true);
  draw_curves(dl, top, p.r_mm, p.model_rR, 0, 2.0f);
  draw_curves(dl, top, p.r_mm, p.fit_rR, 2, 1.0f);
  draw_curves(dl, top, p.r_mm, p.model_rT, 3, 2.0f);
  dl->PopClipRect();
  if (with_error) {
    LogAxes err = top;
    err.p0.y = top.p1.y + 6.0f;
    err.p1.y = err.p0.y + err_h;
    err.y = {-4, 0};
    draw_axes(dl, err, true, "rel. error");
    dl->PushClipRect(err.p0, err.p1, true);
    draw_curves(dl, err, p.r_mm, p.rel_error, 0, 1.0f);
    dl->PopClipRect();
  }
  dl->AddText(ImVec2(origin.x, origin.y + total_h - 13), IM_COL32(200, 200, 200, 255), "mm");
  dl->PopClipRect();
}

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
  if (!error_.empty()) ImGui::TextColored(kErrorColor, "%s", error_.c_str());
  ImGui::PopItemWidth();
  ImGui::End();
}

void ViewerUi::draw_sss(renderer::Renderer& r) {
  if (!ImGui::CollapsingHeader("SSS", ImGuiTreeNodeFlags_DefaultOpen)) return;
  renderer::RenderOptions o = r.options();
  int mode = o.sss == renderer::SssMode::Off       ? 0
             : o.sss == renderer::SssMode::Texture ? 3
             : (o.kind == renderer::SssKind::Separable ? 1 : 2);
  const char* modes[] = {"off", "screen: separable", "screen: gaussians", "texture space"};
  bool changed = false;
  if (ImGui::BeginCombo("mode", modes[mode])) {
    for (int k = 0; k < 4; ++k)
      if (ImGui::Selectable(modes[k], k == mode)) {
        changed |= k != mode;
        mode = k;
      }
    ImGui::EndCombo();
  }
  if (mode == 3) changed |= draw_texture_objects(r, o);
  changed |= ImGui::SliderFloat("exposure", &o.exposure, 0.05f, 8.0f, "%.2f",
                                ImGuiSliderFlags_Logarithmic);
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
  const char* legend = nullptr;
  switch (o.debug_view) {
    case renderer::DebugView::KernelRadius:
      legend = "kernel radius in px on a log2 scale (automatic: 1 px to the largest radius "
               "on screen); magenta < 1 px (the screen kernel undersamples the profile)";
      break;
    case renderer::DebugView::Thickness:
      legend = "mm through the object along light 0 (automatic: 0 to the largest SSS "
               "object's size); grey: no shadow map there";
      break;
    case renderer::DebugView::UvStretch:
      legend = "mm per unit of u (red) and v (green), automatic: 0 to pi x the largest SSS "
               "object's size; grey: no UVs";
      break;
    case renderer::DebugView::ProfileId: legend = "one flat colour per material"; break;
    default: break;
  }
  if (legend != nullptr) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", legend);
    ImGui::PopStyleColor();
  }
  if (!changed) return;
  o.sss = mode == 0 ? renderer::SssMode::Off
          : mode == 3 ? renderer::SssMode::Texture
                      : renderer::SssMode::Screen;
  if (mode == 1 || mode == 2)
    o.kind = mode == 1 ? renderer::SssKind::Separable : renderer::SssKind::Gaussians;
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
  for (const std::string& w : texture->warnings()) ImGui::TextColored(kErrorColor, "%s", w.c_str());
  return changed;
}

void ViewerUi::draw_materials(renderer::Renderer& /*r*/) {
  if (editor_.edits().empty() || !ImGui::CollapsingHeader("Materials", ImGuiTreeNodeFlags_DefaultOpen))
    return;
  const RefitLatency& l = editor_.latency();
  if (editor_.fitting())
    ImGui::TextColored(kWarningColor, "fitting...");
  else if (l.edits > 0)
    ImGui::TextDisabled("fit %.0f, upload %.1f, edit->frame %.0f ms", l.fit_ms, l.upload_ms,
                        l.edit_to_frame_ms);
  // Every material of the scene (issue 20): those with SSS open, the others closed, each
  // with its "enable subsurface" switch.
  for (std::size_t i = 0; i < editor_.edits().size(); ++i) {
    MaterialEdit& e = editor_.edits()[i];
    ImGui::PushID(int(e.index));
    const ImGuiTreeNodeFlags open = e.enabled ? ImGuiTreeNodeFlags_DefaultOpen : 0;
    if (ImGui::TreeNodeEx("material", open, "%s%s", e.name.c_str(), e.enabled ? "" : " (opaque)")) {
      bool on = e.enabled;
      if (ImGui::Checkbox("enable subsurface", &on)) editor_.set_enabled(i, on);
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", e.enabled
            ? "off: an opaque PBR surface; the fields stay for the next switch on"
            : "scatter light under this surface: skin1 at scale 1 to start, as "
              "--sss-material NAME=skin1 (texture-space mode needs the material at load)");
      if (e.enabled)
        draw_material(e, i);
      else if (!e.error.empty())
        ImGui::TextColored(kErrorColor, "%s", e.error.c_str());
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

bool ViewerUi::draw_layers(MaterialEdit& e, std::size_t i) {
  ImGui::TextDisabled("model layered, %zu layers, top first", e.layers.size());
  const ImGuiInputTextFlags typed = ImGuiInputTextFlags_CharsScientific;
  bool apply = false;
  // A button's change to the stack waits until the rows are drawn (the loop walks it).
  enum class Op { None, Split, Remove, Up, Down } op = Op::None;
  std::size_t at = 0;
  for (std::size_t k = 0; k < e.layers.size(); ++k) {
    LayerEdit& l = e.layers[k];
    ImGui::PushID(int(k));
    const bool last = k + 1 == e.layers.size();
    ImGui::Separator();
    ImGui::Text("layer %zu%s", k, last && l.thickness_mm == 0.0f ? " (semi-infinite)" : "");
    ImGui::SameLine();
    if (ImGui::SmallButton("split")) op = Op::Split, at = k;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("two identical layers in its place (the look stays)");
    ImGui::SameLine();
    ImGui::BeginDisabled(k == 0);
    if (ImGui::SmallButton("up")) op = Op::Up, at = k;
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(last);
    if (ImGui::SmallButton("down")) op = Op::Down, at = k;
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::SmallButton("remove")) op = Op::Remove, at = k;
    ImGui::InputFloat3("sigma_a 1/mm", l.sigma_a.data(), "%.4g", typed);
    apply |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::InputFloat3("sigma_s 1/mm", l.sigma_s.data(), "%.4g", typed);
    apply |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::InputFloat3("g", l.g.data(), "%.3g", typed);
    apply |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::InputFloat("thickness mm", &l.thickness_mm, 0.0f, 0.0f, "%.3g", typed);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("mm; 0: semi-infinite (the last layer only); a layer must be thicker "
                        "than its 1/sigma_t'");
    apply |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::PopID();
  }
  ImGui::Separator();
  ImGui::InputFloat3("eta (all)", e.eta.data(), "%.3g", typed);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("every layer's: the interfaces are index-matched");
  apply |= ImGui::IsItemDeactivatedAfterEdit();
  switch (op) {  // each applies the stack itself
    case Op::Split: editor_.add_layer(i, at); return false;
    case Op::Remove: editor_.remove_layer(i, at); return false;
    case Op::Up: editor_.move_layer(i, at, -1); return false;
    case Op::Down: editor_.move_layer(i, at, +1); return false;
    case Op::None: break;
  }
  return apply;
}

void ViewerUi::draw_material(MaterialEdit& e, std::size_t i) {
  const bool layered = !e.layers.empty();
  const auto all = profiles::presets();
  const int shown_preset = e.kind == SourceKind::Preset ? e.preset : -1;
  if (ImGui::BeginCombo("preset", preset_label(shown_preset).c_str())) {
    for (int k = 0; k < int(all.size()); ++k)
      if (ImGui::Selectable(preset_label(k).c_str(), k == shown_preset)) editor_.select_preset(i, k);
    ImGui::EndCombo();
  }
  if (layered && ImGui::IsItemHovered()) ImGui::SetTooltip("a preset replaces the stack");
  ImGui::BeginDisabled(layered);  // a stack's model is layered
  if (ImGui::BeginCombo("model", layered ? "layered" : model_label(e.model).c_str())) {
    for (int m = 0; m < int(MaterialEditor::models().size()); ++m)
      if (ImGui::Selectable(model_label(m).c_str(), m == e.model)) editor_.select_model(i, m);
    ImGui::EndCombo();
  }
  int kind = e.kind == SourceKind::Artist ? 1 : e.kind == SourceKind::OpenPbr ? 2 : 0;
  if (ImGui::RadioButton("coefficients", &kind, 0)) editor_.set_source_kind(i, SourceKind::Coefficients);
  ImGui::SameLine();
  if (ImGui::RadioButton("artist", &kind, 1)) editor_.set_source_kind(i, SourceKind::Artist);
  ImGui::SameLine();
  if (ImGui::RadioButton("OpenPBR", &kind, 2)) editor_.set_source_kind(i, SourceKind::OpenPbr);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("OpenPBR's subsurface parameters (Standard Surface's map onto them): the "
                      "colour seen, linear Rec.709; mean free path = radius x radius scale");
  ImGui::EndDisabled();

  // Typed fields apply when the edit ends (Enter, Tab, click away); drags, sliders and
  // the colour picker apply on every change (the refit is asynchronous).
  bool apply = false;
  const ImGuiInputTextFlags typed = ImGuiInputTextFlags_CharsScientific;
  if (layered) {
    apply |= draw_layers(e, i);
  } else if (e.kind == SourceKind::OpenPbr) {
    apply |= ImGui::ColorEdit3("colour##pbr", e.pbr_color.data(), ImGuiColorEditFlags_Float);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("subsurface_color, linear Rec.709, in (0, 1)");
    apply |= ImGui::DragFloat("radius mm", &e.pbr_radius_mm, 0.01f, 0.0f, 0.0f, "%.3g");
    apply |= ImGui::DragFloat3("radius scale", e.pbr_radius_scale.data(), 0.005f, 0.001f, 1.0f, "%.3g");
    apply |= ImGui::SliderFloat("anisotropy", &e.pbr_anisotropy, -0.95f, 0.95f, "%.2f");
    ImGui::InputFloat("specular ior", &e.pbr_ior, 0.0f, 0.0f, "%.3g", typed);
    apply |= ImGui::IsItemDeactivatedAfterEdit();
    const char* inversions[] = {"van de Hulst (spec)", "model's total"};
    apply |= ImGui::Combo("inversion", &e.pbr_inversion, inversions, 2);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("van de Hulst: the spec's index-matched relation, as the Khronos sample "
                        "viewer draws it; model's total: the albedo whose total reflectance "
                        "under the chosen model, with this ior's boundary, is the colour");
  } else if (e.kind != SourceKind::Artist) {
    ImGui::InputFloat3("sigma_a 1/mm", e.sigma_a.data(), "%.4g", typed);
    if (ImGui::IsItemDeactivatedAfterEdit()) { e.kind = SourceKind::Coefficients; apply = true; }
    ImGui::InputFloat3("sigma_s 1/mm", e.sigma_s.data(), "%.4g", typed);
    if (ImGui::IsItemDeactivatedAfterEdit()) { e.kind = SourceKind::Coefficients; apply = true; }
    ImGui::InputFloat3("g", e.g.data(), "%.3g", typed);
    if (ImGui::IsItemDeactivatedAfterEdit()) { e.kind = SourceKind::Coefficients; apply = true; }
    ImGui::InputFloat3("eta", e.eta.data(), "%.3g", typed);
    if (ImGui::IsItemDeactivatedAfterEdit()) { e.kind = SourceKind::Coefficients; apply = true; }
  } else {
    apply |= ImGui::ColorEdit3("colour", e.color.data(), ImGuiColorEditFlags_Float);
    apply |= ImGui::DragFloat3("mfp mm", e.mfp_mm.data(), 0.01f, 0.0f, 0.0f, "%.3g");
    ImGui::InputFloat("eta", &e.artist_eta, 0.0f, 0.0f, "%.3g", typed);
    apply |= ImGui::IsItemDeactivatedAfterEdit();
  }
  if (!layered) {
    ImGui::InputFloat("thickness mm", &e.thickness_mm, 0.0f, 0.0f, "%.3g", typed);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("0: semi-infinite (multipole needs a slab)");
    if (ImGui::IsItemDeactivatedAfterEdit()) {
      if (e.kind == SourceKind::Preset) e.kind = SourceKind::Coefficients;
      apply = true;
    }
    ImGui::BeginDisabled(e.kind == SourceKind::Artist || e.kind == SourceKind::OpenPbr);
    if (ImGui::SmallButton("add layer")) editor_.add_layer(i, 0);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("make this medium a stack of two identical layers (the look stays); then "
                        "edit either layer");
    ImGui::EndDisabled();
  }
  apply |= ImGui::SliderInt("gaussians", &e.gaussians, scene::kMinGaussians, scene::kMaxGaussians);
  apply |= ImGui::SliderFloat("scale", &e.scale, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  const char* albedo[] = {"post-scatter", "pre-post"};
  apply |= ImGui::Combo("albedo", &e.albedo, albedo, 2);
  if (apply) editor_.apply(i);

  if (!e.error.empty()) ImGui::TextColored(kErrorColor, "%s", e.error.c_str());
  if (!e.scale_note.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("%s", e.scale_note.c_str());
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("reduced mean free path 1/sigma_t' and diffusion length 1/sigma_tr (min-max "
                        "over R, G, B, after the scale) against the diameter of what the material "
                        "is drawn on; (%%): the longest diffusion length as a share of it. A "
                        "lower scale scatters further");
  }
  ImGui::PushTextWrapPos(0.0f);  // a warning is a sentence: wrap it at the panel's edge
  for (const std::string& w : e.warnings) ImGui::TextColored(kWarningColor, "%s", w.c_str());
  ImGui::PopTextWrapPos();
  if (e.plot) {
    ImGui::Checkbox("plot error", &plot_error_);
    ImGui::SameLine();
    ImGui::TextDisabled("fit err %.1f/%.1f/%.1f%%", 100.0 * e.plot->fit_relative_error[0],
                        100.0 * e.plot->fit_relative_error[1], 100.0 * e.plot->fit_relative_error[2]);
    draw_profile_plot(*e.plot, plot_error_);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(e.plot->model_rT.empty()
                            ? "r R(r): model solid, Gaussian fit dashed; below: relative error"
                            : "r R(r): model solid, Gaussian fit dashed; r T(r), the light through "
                              "the far face: dotted; below: R's relative error");
  }
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
                      "(split sum); no occlusion on the GPU");
  ImGui::BeginDisabled(!environment_on_);
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
