// A small log-log line plot written as a standalone SVG: axes with decade ticks and
// labels, units, a legend, optional markers with error bars, and note lines.
#pragma once

#include <string>
#include <vector>

namespace sss::app {

struct PlotSeries {
  std::string label;
  std::string color;     // any SVG colour
  bool dashed = false;
  bool markers = false;  // draw points (with error bars when y_err is filled) instead of a line
  std::vector<double> x, y;
  std::vector<double> y_err;  // optional, same size as y
};

struct LogLogPlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotSeries> series;
  std::vector<std::string> notes;  // printed under the legend
  double y_floor_ratio = 1e-5;     // the y axis spans at most this ratio below the peak
};

// The SVG document. Points with x <= 0 or y <= 0 are skipped (log axes).
std::string render_svg(const LogLogPlot& plot);

}  // namespace sss::app
