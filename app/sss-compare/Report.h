// What sss-compare prints: the limits that decide pass or fail, and the report as a table
// or as one JSON document.
#pragma once

#include "image/HeatMap.h"
#include "image/Metrics.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace sss::app {

struct InputInfo {
  std::string path;
  int width = 0, height = 0;
  image::Encoding encoding = image::Encoding::Display;
  bool tonemapped = false;  // a linear image compared with a display one
};

// One limit on one metric: value <= limit, or value >= limit for SSIM.
struct Check {
  std::string metric;  // the JSON name of the metric
  std::string label;   // its name in the table
  double value = 0.0, limit = 0.0;
  bool at_least = false;  // ">=" (SSIM) instead of "<="
  bool pass = false;
};

struct Limits {
  double tolerance = 0.01;  // on the relative RMSE, always applied
  std::optional<double> max_abs, max_fraction, min_ssim;
};

std::vector<Check> evaluate(const image::Metrics& m, const Limits& limits);
bool all_pass(const std::vector<Check>& checks);

struct Report {
  InputInfo a, b;
  image::Encoding space = image::Encoding::Display;  // where the metrics were taken
  float exposure = 1.0f;
  image::Metrics metrics;
  Limits limits;
  std::vector<Check> checks;
  // --exclude-silhouettes: the pixels with geometry in both that it left out.
  std::optional<std::size_t> silhouette_pixels;
  std::optional<std::string> heatmap;  // the file written, if any
  double heatmap_max = 0.0;            // its scale's top (signed: -top to +top)
  std::string heatmap_scale;           // "given" (--heatmap-max), "p99", "max" or "none"
  bool heatmap_signed = false;
  std::size_t heatmap_above = 0;  // compared pixels whose |error| is above the top
  std::optional<std::string> log_ratio;  // the --log-ratio file written, if any
  double log_range = 0.0;                // its range in stops
  image::LogRatioStats log_stats;        // of log2(A/B), with --log-ratio
};

nlohmann::ordered_json to_json(const Report& r);
std::string to_table(const Report& r);

}  // namespace sss::app
