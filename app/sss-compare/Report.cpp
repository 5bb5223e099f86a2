#include "Report.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace sss::app {

namespace {

// JSON has no infinities or NaN: those become null (documented in the README).
nlohmann::ordered_json number(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); }

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char buf[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

std::string g(double v) {
  if (std::isnan(v)) return "undefined";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return format("%.6g", v);
}

nlohmann::ordered_json input_json(const InputInfo& in) {
  return {{"path", in.path},
          {"width", in.width},
          {"height", in.height},
          {"encoding", image::encoding_name(in.encoding)},
          {"tonemapped", in.tonemapped}};
}

const Check* find_check(const Report& r, const std::string& metric) {
  for (const Check& c : r.checks)
    if (c.metric == metric) return &c;
  return nullptr;
}

}  // namespace

std::vector<Check> evaluate(const image::Metrics& m, const Limits& limits) {
  std::vector<Check> checks;
  auto add = [&](const char* metric, const char* label, double value, double limit, bool at_least) {
    // NaN and +inf never pass an upper limit; NaN never passes a lower one.
    const bool pass = at_least ? value >= limit : value <= limit;
    checks.push_back({metric, label, value, limit, at_least, pass});
  };
  // With the reference's noise known, the tolerance judges the error against its expectation.
  if (m.has_reference_noise)
    add("relative_rmse_noise_subtracted", "relative RMSE, noise subtracted", m.relative_rmse_noise_subtracted,
        limits.tolerance, false);
  else
    add("relative_rmse", "relative RMSE", m.relative_rmse, limits.tolerance, false);
  if (limits.max_abs) add("max_abs_error", "max abs error", m.max_abs_error, *limits.max_abs, false);
  if (limits.max_fraction)
    add("fraction_over_threshold", "over threshold", m.fraction_over_threshold,
        *limits.max_fraction, false);
  if (limits.min_ssim) add("ssim", "SSIM", m.ssim, *limits.min_ssim, true);
  return checks;
}

bool all_pass(const std::vector<Check>& checks) {
  for (const Check& c : checks)
    if (!c.pass) return false;
  return true;
}

nlohmann::ordered_json to_json(const Report& r) {
  const image::Metrics& m = r.metrics;
  nlohmann::ordered_json limits = nlohmann::ordered_json::array();
  for (const Check& c : r.checks)
    limits.push_back({{"metric", c.metric},
                      {"op", c.at_least ? ">=" : "<="},
                      {"limit", c.limit},
                      {"value", number(c.value)},
                      {"pass", c.pass}});
  nlohmann::ordered_json heatmap;  // null without --heatmap
  if (r.heatmap)
    heatmap = {{"path", *r.heatmap},
               {"max", r.heatmap_max},
               {"scale", r.heatmap_scale},
               {"signed", r.heatmap_signed},
               {"pixels_above", r.heatmap_above}};
  nlohmann::ordered_json log_ratio;  // null without --log-ratio
  if (r.log_ratio)
    log_ratio = {{"path", *r.log_ratio},
                 {"range_stops", r.log_range},
                 {"mean_log2", number(r.log_stats.mean_log2)},
                 {"mean_abs_log2", number(r.log_stats.mean_abs_log2)},
                 {"tolerance", r.log_stats.tolerance},
                 {"fraction_brighter", number(r.log_stats.fraction_brighter)},
                 {"fraction_darker", number(r.log_stats.fraction_darker)}};
  return {
      {"a", input_json(r.a)},
      {"b", input_json(r.b)},
      {"space", image::encoding_name(r.space)},
      {"exposure", r.exposure},
      {"pixels",
       {{"total", m.total_pixels},
        {"compared", m.compared_pixels},
        {"excluded", m.total_pixels - m.compared_pixels},
        {"silhouette", r.silhouette_pixels ? nlohmann::ordered_json(*r.silhouette_pixels)
                                           : nlohmann::ordered_json()}}},
      {"metrics",
       {{"rmse", number(m.rmse)},
        {"relative_rmse", number(m.relative_rmse)},
        {"peak", number(m.peak)},
        {"psnr_db", number(m.psnr_db)},
        {"max_abs_error", number(m.max_abs_error)},
        {"max_abs_error_at", {m.max_abs_x, m.max_abs_y}},
        {"pixels_over_threshold", m.pixels_over_threshold},
        {"fraction_over_threshold", number(m.fraction_over_threshold)},
        {"ssim", number(m.ssim)},
        {"sum_ratio", {number(m.sum_ratio[0]), number(m.sum_ratio[1]), number(m.sum_ratio[2])}},
        {"reference_noise", m.has_reference_noise ? number(m.reference_noise) : nlohmann::ordered_json()},
        {"relative_rmse_noise_subtracted",
         m.has_reference_noise ? number(m.relative_rmse_noise_subtracted) : nlohmann::ordered_json()}}},
      {"threshold", m.threshold},
      {"tolerance", r.limits.tolerance},
      {"limits", limits},
      {"pass", all_pass(r.checks)},
      {"heatmap", heatmap},
      {"log_ratio", log_ratio},
  };
}

namespace {

// The inputs' lines and what was compared.
std::string table_header(const Report& r) {
  const image::Metrics& m = r.metrics;
  std::string out;
  for (const auto* in : {&r.a, &r.b}) {
    out += format("%s  %s  %dx%d  %s", in == &r.a ? "A (test)     " : "B (reference)", in->path.c_str(),
                  in->width, in->height, image::encoding_name(in->encoding));
    if (in->tonemapped) out += format(", tonemapped at exposure %g to compare", r.exposure);
    out += '\n';
  }
  const std::size_t silhouette = r.silhouette_pixels.value_or(0);
  out += format("compared %zu of %zu pixels (%zu without geometry in A or B%s), %s values, peak %s\n\n",
                m.compared_pixels, m.total_pixels, m.total_pixels - m.compared_pixels - silhouette,
                r.silhouette_pixels ? format(", %zu at a silhouette", silhouette).c_str() : "",
                image::encoding_name(r.space), g(m.peak).c_str());
  return out;
}

// One row per metric, with its limit and verdict where one was checked.
std::string table_metrics(const Report& r) {
  const image::Metrics& m = r.metrics;
  std::string out;
  auto row = [&](const std::string& label, const std::string& value, const std::string& note,
                 const char* metric) {
    std::string limit;
    if (const Check* c = metric ? find_check(r, metric) : nullptr)
      limit = format("%s %-10s %s", c->at_least ? ">=" : "<=", g(c->limit).c_str(),
                     c->pass ? "ok" : "FAIL");
    std::string line = format("%-24s %-14s %-20s %s", label.c_str(), value.c_str(), limit.c_str(),
                              note.c_str());
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + '\n';
  };
  out += format("%-24s %-14s %s\n", "metric", "value", "limit");
  row("relative RMSE", g(m.relative_rmse), "", "relative_rmse");
  if (m.has_reference_noise) {
    row("reference noise", g(m.reference_noise), "B's relative RMS noise (--variance)", nullptr);
    row("rel. RMSE - noise", g(m.relative_rmse_noise_subtracted), "against B's expectation",
        "relative_rmse_noise_subtracted");
  }
  row("RMSE", g(m.rmse), "", nullptr);
  row("PSNR (dB)", g(m.psnr_db), "", nullptr);
  row("max abs error", g(m.max_abs_error), format("at (%d, %d)", m.max_abs_x, m.max_abs_y), "max_abs_error");
  row(format("over threshold %s", g(m.threshold).c_str()), g(m.fraction_over_threshold),
      format("%zu pixels with error > %s", m.pixels_over_threshold, g(m.threshold * m.peak).c_str()),
      "fraction_over_threshold");
  row("SSIM", g(m.ssim), "", "ssim");
  row("summed A / B", format("%.4f %.4f %.4f", m.sum_ratio[0], m.sum_ratio[1], m.sum_ratio[2]),
      "R G B: the bias", nullptr);
  return out;
}

// The heat map's and the log-ratio map's lines, where they were written.
std::string table_maps(const Report& r) {
  std::string out;
  if (r.heatmap) {
    const char* why = r.heatmap_scale == "p99"    ? ", the 99th percentile"
                      : r.heatmap_scale == "max"  ? ", the largest error"
                      : r.heatmap_scale == "none" ? ", no error"
                                                  : "";
    if (r.heatmap_signed)
      out += format("\nheat map: %s (signed error a-b, -%s to +%s%s; red A above, blue below)\n",
                    r.heatmap->c_str(), g(r.heatmap_max).c_str(), g(r.heatmap_max).c_str(), why);
    else
      out += format("\nheat map: %s (error 0 to %s%s)\n", r.heatmap->c_str(), g(r.heatmap_max).c_str(), why);
    if (r.heatmap_above > 0)
      out += format("  %zu pixels above the scale, drawn at its end\n", r.heatmap_above);
  }
  if (r.log_ratio) {
    const image::LogRatioStats& s = r.log_stats;
    out += format("%slog ratio map: %s (log2(A/B) of the luminance, -%s to +%s stops)\n",
                  r.heatmap ? "" : "\n", r.log_ratio->c_str(), g(r.log_range).c_str(),
                  g(r.log_range).c_str());
    out += format("  mean log2(A/B) %s (mean |log2| %s); beyond +-%s%%: %s brighter, %s darker\n",
                  g(s.mean_log2).c_str(), g(s.mean_abs_log2).c_str(), g(100.0 * s.tolerance).c_str(),
                  g(s.fraction_brighter).c_str(), g(s.fraction_darker).c_str());
  }
  return out;
}

}  // namespace

std::string to_table(const Report& r) {
  std::string out = table_header(r) + table_metrics(r) + table_maps(r);
  std::string failed;
  for (const Check& c : r.checks)
    if (!c.pass)
      failed += format("%s%s %s %s %s", failed.empty() ? "" : "; ", c.label.c_str(),
                       g(c.value).c_str(), c.at_least ? "<" : ">", g(c.limit).c_str());
  out += failed.empty() ? "\nresult: PASS\n" : "\nresult: FAIL (" + failed + ")\n";
  return out;
}

}  // namespace sss::app
