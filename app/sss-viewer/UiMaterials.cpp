// The material panel: each SSS material's fields, its layers and its profile plot.
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
              "--sss-material NAME=skin1 (texture space builds the mesh's UV atlas if it needs one)");
      if (e.enabled)
        draw_material(e, i);
      else if (!e.error.empty())
        colored_text_wrapped(kErrorColor, e.error.c_str());
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

namespace {

// What a layer row's button or menu asks for; done after the rows are drawn (the loop
// walks the stack it would change).
struct LayerOp {
  enum class Kind { None, Split, Remove, Up, Down, Preset, PresetWithItsEta } kind = Kind::None;
  std::size_t at = 0;
  int preset = -1;  // Kind::Preset's
};

// Layer k's row: its buttons, preset menu, coefficients and thickness. True when a typed
// field's edit ended (a typed coefficient also makes the layer "(custom)").
bool draw_layer_row(LayerEdit& l, std::size_t k, bool last, LayerOp& op) {
  using Kind = LayerOp::Kind;
  const ImGuiInputTextFlags typed = ImGuiInputTextFlags_CharsScientific;
  ImGui::Separator();
  ImGui::Text("layer %zu%s", k, last && l.thickness_mm == 0.0f ? " (semi-infinite)" : "");
  ImGui::SameLine();
  if (ImGui::SmallButton("split")) op = {Kind::Split, k};
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("two identical layers in its place (the look stays)");
  ImGui::SameLine();
  ImGui::BeginDisabled(k == 0);
  if (ImGui::SmallButton("up")) op = {Kind::Up, k};
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(last);
  if (ImGui::SmallButton("down")) op = {Kind::Down, k};
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::SmallButton("remove")) op = {Kind::Remove, k};
  if (ImGui::BeginCombo("preset", preset_label(l.preset).c_str())) {
    for (int p = 0; p < int(profiles::presets().size()); ++p)
      if (ImGui::Selectable(preset_label(p).c_str(), p == l.preset)) op = {Kind::Preset, k, p};
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("this layer's sigma_a, sigma_s and g from a preset; its thickness stays");
  bool typed_edit = false;
  ImGui::InputFloat3("sigma_a 1/mm", l.sigma_a.data(), "%.4g", typed);
  typed_edit |= ImGui::IsItemDeactivatedAfterEdit();
  ImGui::InputFloat3("sigma_s 1/mm", l.sigma_s.data(), "%.4g", typed);
  typed_edit |= ImGui::IsItemDeactivatedAfterEdit();
  ImGui::InputFloat3("g", l.g.data(), "%.3g", typed);
  typed_edit |= ImGui::IsItemDeactivatedAfterEdit();
  if (typed_edit) l.preset = -1;
  ImGui::InputFloat("thickness mm", &l.thickness_mm, 0.0f, 0.0f, "%.3g", typed);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("mm; 0: semi-infinite (the last layer only); a layer must be thicker "
                      "than its 1/sigma_t'");
  return typed_edit || ImGui::IsItemDeactivatedAfterEdit();
}

}  // namespace

bool ViewerUi::draw_layers(MaterialEdit& e, std::size_t i) {
  ImGui::TextDisabled("model layered, %zu layers, top first", e.layers.size());
  bool apply = false;
  LayerOp op;
  for (std::size_t k = 0; k < e.layers.size(); ++k) {
    ImGui::PushID(int(k));
    apply |= draw_layer_row(e.layers[k], k, k + 1 == e.layers.size(), op);
    ImGui::PopID();
  }
  ImGui::Separator();
  ImGui::InputFloat3("eta (all)", e.eta.data(), "%.3g", ImGuiInputTextFlags_CharsScientific);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("every layer's: the interfaces are index-matched");
  apply |= ImGui::IsItemDeactivatedAfterEdit();
  if (e.eta_offer) {  // a layer preset refused for its eta: offer it with its eta for all
    const MaterialEdit::EtaOffer& offer = *e.eta_offer;
    const std::string label = "use " + preset_label(offer.preset) + " with eta " +
                              message_number(offer.eta[0]) + " for every layer";
    if (ImGui::SmallButton(label.c_str())) op = {LayerOp::Kind::PresetWithItsEta, offer.layer, offer.preset};
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("the stack's interfaces are index-matched: every layer takes the preset's eta");
  }
  switch (op.kind) {  // each applies the stack itself
    case LayerOp::Kind::Split: editor_.add_layer(i, op.at); return false;
    case LayerOp::Kind::Remove: editor_.remove_layer(i, op.at); return false;
    case LayerOp::Kind::Up: editor_.move_layer(i, op.at, -1); return false;
    case LayerOp::Kind::Down: editor_.move_layer(i, op.at, +1); return false;
    case LayerOp::Kind::Preset: editor_.set_layer_preset(i, op.at, op.preset); return false;
    case LayerOp::Kind::PresetWithItsEta: editor_.set_layer_preset(i, op.at, op.preset, true); return false;
    case LayerOp::Kind::None: break;
  }
  return apply;
}

void ViewerUi::draw_source(MaterialEdit& e, std::size_t i, bool layered) {
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
}

// The medium's own fields (a stack's layers, OpenPBR, coefficients or artist) and its
// thickness; true when an edit asks for a refit.
bool ViewerUi::draw_medium(MaterialEdit& e, std::size_t i, bool layered) {
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
  return apply;
}

// The fit's error, the scale's note, the warnings and the profile plot.
void ViewerUi::draw_material_status(MaterialEdit& e) {
  if (!e.error.empty()) colored_text_wrapped(kErrorColor, e.error.c_str());
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
  for (const std::string& w : e.warnings) colored_text_wrapped(kWarningColor, w.c_str());
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

void ViewerUi::draw_material(MaterialEdit& e, std::size_t i) {
  // As the frame began: a preset chosen now replaces a stack from the next frame.
  const bool layered = !e.layers.empty();
  draw_source(e, i, layered);
  bool apply = draw_medium(e, i, layered);
  apply |= ImGui::SliderInt("gaussians", &e.gaussians, scene::kMinGaussians, scene::kMaxGaussians);
  apply |= ImGui::SliderFloat("scale", &e.scale, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  const char* albedo[] = {"post-scatter", "pre-post"};
  apply |= ImGui::Combo("albedo", &e.albedo, albedo, 2);
  if (apply) editor_.apply(i);
  draw_material_status(e);
}

}  // namespace sss::app
