// The Compare section's results: the metrics table, the error maps (absolute or signed
// log ratio, for each pair of frame, reference and ground truth) and their controls.
#include "Tools.h"

#include "image/HeatMap.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <utility>

namespace sss::app {

namespace {

std::pair<const char*, const char*> pair_operands(ViewerTools::Pair p) {
  switch (p) {
    case ViewerTools::Pair::FrameVsReference: return {"frame", "reference"};
    case ViewerTools::Pair::FrameVsTruth: return {"frame", "truth"};
    case ViewerTools::Pair::ReferenceVsTruth: return {"reference", "truth"};
  }
  return {"?", "?"};
}

}  // namespace

std::string ViewerTools::pair_name(Pair p) {
  const auto [a, b] = pair_operands(p);
  return std::string(a) + " vs " + b;
}

std::string ViewerTools::ratio_name(Pair p) {
  const auto [a, b] = pair_operands(p);
  return "log2(" + std::string(a) + "/" + b + ")";
}

void ViewerTools::render_map() {
  map_image_ = {};
  heat_image_ = {};
  const std::optional<PairResult>& res = results_[int(pair_)];
  if (!res) return;
  try {
    const int w = res->width, h = res->height;
    const image::Image canvas =
        map_ == ErrorMap::Absolute
            ? image::render_heatmap(res->errors, res->mask, w, h, res->heat_max)
            : image::render_log_ratio_map(res->log2_ratio, res->mask, w, h, log_range_);
    image::Image map(w, h);  // the map, without the colour bar (the panel draws that)
    for (int y = 0; y < h; ++y) std::copy_n(canvas.pixel(0, y), 4 * std::size_t(w), map.pixel(0, y));
    for (std::size_t i = 3; i < map.rgba.size(); i += 4) map.rgba[i] = 1.0f;
    heat_image_ = upload(map, "compare error map");
    map_image_ = std::move(map);
  } catch (const std::exception& e) {
    compare_error_ = e.what();
  }
}

void ViewerTools::set_error_map(ErrorMap map, Pair pair) {
  map_ = map;
  pair_ = pair;
  view_ = 3;
  expand_ = true;
  render_map();
}

void ViewerTools::set_log_range(double stops) {
  if (!(std::isfinite(stops) && stops > 0.0)) return;
  log_range_ = stops;
  if (map_ == ErrorMap::LogRatio) render_map();
}

void ViewerTools::draw_metrics() {
  int columns = 0;
  for (const auto& res : results_) columns += res.has_value();
  if (columns == 0) return;
  if (!ImGui::BeginTable("metrics", 1 + columns, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg))
    return;
  static const char* kShort[kPairs] = {"frame/ref", "frame/truth", "ref/truth"};
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  for (int p = 0; p < kPairs; ++p)
    if (results_[p]) {
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(kShort[p]);
    }
  const auto row = [&](const char* label, const char* tooltip, auto value) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(label);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tooltip);
    for (const auto& res : results_)
      if (res) {
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(value(*res).c_str());
      }
  };
  const auto fmt = [](const char* f, double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, f, v);
    return std::string(buf);
  };
  row("rel. RMSE", "sqrt(sum (a-b)^2 / sum b^2) of the display codes",
      [&](const PairResult& x) { return fmt("%.2f%%", 100.0 * x.metrics.relative_rmse); });
  row("PSNR", "dB, peak 1", [&](const PairResult& x) { return fmt("%.1f", x.metrics.psnr_db); });
  row("SSIM", "mean SSIM of the luma", [&](const PairResult& x) { return fmt("%.4f", x.metrics.ssim); });
  row("max |err|", "the largest max_c |a-b|",
      [&](const PairResult& x) { return fmt("%.3f", x.metrics.max_abs_error); });
  row("> 5% peak", "pixels whose error exceeds 5% of the peak",
      [&](const PairResult& x) { return fmt("%.2f%%", 100.0 * x.metrics.fraction_over_threshold); });
  row("mean log2", "mean log2(A/B) of the linear luminance: the bias in stops",
      [&](const PairResult& x) { return fmt("%+.3f", x.log_stats.mean_log2); });
  row("> +5%", "pixels more than 5% brighter than B (A > 1.05 B)",
      [&](const PairResult& x) { return fmt("%.2f%%", 100.0 * x.log_stats.fraction_brighter); });
  row("< -5%", "pixels more than 5% darker than B (A < B / 1.05)",
      [&](const PairResult& x) { return fmt("%.2f%%", 100.0 * x.log_stats.fraction_darker); });
  ImGui::EndTable();
  if (const auto& m = results_[0])
    ImGui::TextWrapped("frame/ref: max |err| at (%d, %d); %zu pixels compared", m->metrics.max_abs_x,
                       m->metrics.max_abs_y, m->metrics.compared_pixels);
}

void ViewerTools::draw_map_controls() {
  if (ImGui::BeginCombo("pair", pair_name(pair_).c_str())) {
    for (int p = 0; p < kPairs; ++p) {
      if (!results_[p]) continue;
      if (ImGui::Selectable(pair_name(Pair(p)).c_str(), pair_ == Pair(p)) && pair_ != Pair(p)) {
        pair_ = Pair(p);
        render_map();
      }
    }
    ImGui::EndCombo();
  }
  int map = int(map_);
  bool changed = ImGui::RadioButton("absolute error", &map, int(ErrorMap::Absolute));
  const std::string ratio = std::string("signed log ratio ") + ratio_name(pair_);
  changed |= ImGui::RadioButton(ratio.c_str(), &map, int(ErrorMap::LogRatio));
  if (changed && map != int(map_)) {
    map_ = ErrorMap(map);
    render_map();
  }
  std::optional<PairResult>& res = results_[int(pair_)];
  if (!res) return;
  // The colour bar (the uploaded map has none).
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x, h = 12.0f;
  constexpr int kSteps = 32;
  for (int i = 0; i < kSteps; ++i) {
    const double t = (i + 0.5) / kSteps;
    const image::Rgb c = map_ == ErrorMap::Absolute ? image::viridis(t) : image::diverging(2.0 * t - 1.0);
    dl->AddRectFilled(ImVec2(p.x + w * i / kSteps, p.y), ImVec2(p.x + w * (i + 1) / kSteps, p.y + h),
                      ImGui::GetColorU32(ImVec4(c[0], c[1], c[2], 1.0f)));
  }
  ImGui::Dummy(ImVec2(w, h));
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  if (map_ == ErrorMap::Absolute) {
    ImGui::PopStyleColor();
    float top = float(res->heat_max);
    if (ImGui::SliderFloat("top", &top, 1e-3f, 1.0f, "%.3f", ImGuiSliderFlags_Logarithmic)) {
      res->heat_max = top;
      render_map();
    }
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("|error| of the display codes, 0 to top (default: 99th percentile); "
                       "grey: no geometry in one image");
  } else {
    ImGui::Text("-%.2g stops %*s0%*s+%.2g stops", log_range_, 10, "", 10, "", log_range_);
    ImGui::PopStyleColor();
    float range = float(log_range_);
    if (ImGui::SliderFloat("range (stops)", &range, 0.05f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
      set_log_range(range);
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s of the linear luminance: blue A darker, white equal, red A brighter, "
                       "saturated beyond +-range (1 stop = 2x); grey: no geometry in one image; "
                       "green: a non-finite value",
                       ratio_name(pair_).c_str());
  }
  ImGui::PopStyleColor();
}

}  // namespace sss::app
