#include "SvgPlot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace sss::app {

namespace {

constexpr double kWidth = 900, kHeight = 560;
constexpr double kLeft = 90, kRight = 250, kTop = 50, kBottom = 70;  // margins

std::string escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string decade_label(int e) {
  if (e == 0) return "1";
  if (e == 1) return "10";
  if (e == -1) return "0.1";
  if (e == -2) return "0.01";
  return "1e" + std::to_string(e);
}

struct Axes {
  double x0, x1, y0, y1;  // log10 bounds
  double px(double x) const {
    return kLeft + (std::log10(x) - x0) / (x1 - x0) * (kWidth - kLeft - kRight);
  }
  double py(double y) const {
    return kHeight - kBottom - (std::log10(y) - y0) / (y1 - y0) * (kHeight - kTop - kBottom);
  }
  bool inside_y(double y) const { return std::log10(y) >= y0 - 1e-9; }
};

// The plot's decades: the bounds of every positive point, y down to y_floor_ratio of its
// top (ymin), widened to whole decades, at least one each way.
Axes axes_for(const LogLogPlot& plot, double& ymin) {
  double xmin = std::numeric_limits<double>::infinity(), xmax = 0, ymax = 0;
  for (const auto& s : plot.series)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0) {
        xmin = std::min(xmin, s.x[i]);
        xmax = std::max(xmax, s.x[i]);
        ymax = std::max(ymax, s.y[i]);
      }
  if (!(xmax > 0)) xmin = 0.1, xmax = 10, ymax = 1;
  ymin = ymax * plot.y_floor_ratio;
  Axes ax{std::floor(std::log10(xmin)), std::ceil(std::log10(xmax)),
          std::floor(std::log10(ymin)), std::ceil(std::log10(ymax))};
  if (ax.x1 <= ax.x0) ax.x1 = ax.x0 + 1;
  if (ax.y1 <= ax.y0) ax.y1 = ax.y0 + 1;
  return ax;
}

constexpr double kPlotLeft = kLeft, kPlotRight = kWidth - kRight, kPlotTop = kTop, kPlotBottom = kHeight - kBottom;

// Grid and ticks: decades labelled, 2..9 as minor ticks.
void write_grid(std::ostringstream& o, const Axes& ax) {
  const double left = kPlotLeft, right = kPlotRight, top = kPlotTop, bottom = kPlotBottom;
  for (int e = static_cast<int>(ax.x0); e <= static_cast<int>(ax.x1); ++e) {
    for (int m = 1; m <= 9; ++m) {
      const double v = m * std::pow(10.0, e);
      if (std::log10(v) > ax.x1 + 1e-9) break;
      const double x = ax.px(v);
      o << "<line x1=\"" << fmt(x) << "\" y1=\"" << top << "\" x2=\"" << fmt(x) << "\" y2=\""
        << bottom << "\" stroke=\"" << (m == 1 ? "#ccc" : "#eee") << "\"/>\n";
      if (m == 1)
        o << "<text x=\"" << fmt(x) << "\" y=\"" << bottom + 18
          << "\" text-anchor=\"middle\">" << decade_label(e) << "</text>\n";
    }
  }
  for (int e = static_cast<int>(ax.y0); e <= static_cast<int>(ax.y1); ++e) {
    for (int m = 1; m <= 9; ++m) {
      const double v = m * std::pow(10.0, e);
      if (std::log10(v) > ax.y1 + 1e-9) break;
      const double y = ax.py(v);
      o << "<line x1=\"" << left << "\" y1=\"" << fmt(y) << "\" x2=\"" << right << "\" y2=\""
        << fmt(y) << "\" stroke=\"" << (m == 1 ? "#ccc" : "#eee") << "\"/>\n";
      if (m == 1)
        o << "<text x=\"" << left - 8 << "\" y=\"" << fmt(y + 4)
          << "\" text-anchor=\"end\">" << decade_label(e) << "</text>\n";
    }
  }
}

// The series, clipped to the plot area: markers (with error bars) or polylines, values
// below ymin drawn at ymin / 1000.
void write_series(std::ostringstream& o, const Axes& ax, const LogLogPlot& plot, double ymin) {
  const double left = kPlotLeft, right = kPlotRight, top = kPlotTop, bottom = kPlotBottom;
  o << "<clipPath id=\"area\"><rect x=\"" << left << "\" y=\"" << top << "\" width=\""
    << right - left << "\" height=\"" << bottom - top << "\"/></clipPath>\n";
  o << "<g clip-path=\"url(#area)\">\n";
  for (const auto& s : plot.series) {
    if (s.markers) {
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!(s.x[i] > 0 && s.y[i] > 0) || !ax.inside_y(s.y[i])) continue;
        const double x = ax.px(s.x[i]), y = ax.py(s.y[i]);
        if (i < s.y_err.size() && s.y_err[i] > 0) {
          const double lo = std::max(s.y[i] - s.y_err[i], ymin * 1e-3);
          o << "<line x1=\"" << fmt(x) << "\" y1=\"" << fmt(ax.py(lo)) << "\" x2=\"" << fmt(x)
            << "\" y2=\"" << fmt(ax.py(s.y[i] + s.y_err[i])) << "\" stroke=\"" << s.color
            << "\"/>\n";
        }
        o << "<circle cx=\"" << fmt(x) << "\" cy=\"" << fmt(y) << "\" r=\"2.5\" fill=\"none\" stroke=\""
          << s.color << "\"/>\n";
      }
      continue;
    }
    o << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"1.8\""
      << (s.dashed ? " stroke-dasharray=\"6,4\"" : "") << " points=\"";
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0)
        o << fmt(ax.px(s.x[i])) << ',' << fmt(ax.py(std::max(s.y[i], ymin * 1e-3))) << ' ';
    o << "\"/>\n";
  }
  o << "</g>\n";

}

// Legend and notes to the right of the plot.
void write_legend(std::ostringstream& o, const LogLogPlot& plot) {
  const double right = kPlotRight, top = kPlotTop;
  double ly = top + 10;
  for (const auto& s : plot.series) {
    const double lx = right + 16;
    if (s.markers)
      o << "<circle cx=\"" << lx + 14 << "\" cy=\"" << ly << "\" r=\"3\" fill=\"none\" stroke=\""
        << s.color << "\"/>\n";
    else
      o << "<line x1=\"" << lx << "\" y1=\"" << ly << "\" x2=\"" << lx + 28 << "\" y2=\"" << ly
        << "\" stroke=\"" << s.color << "\" stroke-width=\"2\""
        << (s.dashed ? " stroke-dasharray=\"6,4\"" : "") << "/>\n";
    o << "<text x=\"" << lx + 36 << "\" y=\"" << ly + 4 << "\">" << escape(s.label)
      << "</text>\n";
    ly += 20;
  }
  ly += 10;
  for (const auto& n : plot.notes) {
    o << "<text x=\"" << right + 16 << "\" y=\"" << ly << "\" font-size=\"12\">" << escape(n)
      << "</text>\n";
    ly += 17;
  }
}

}  // namespace

std::string render_svg(const LogLogPlot& plot) {
  double ymin = 0.0;
  const Axes ax = axes_for(plot, ymin);
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\""
    << kHeight << "\" viewBox=\"0 0 " << kWidth << ' ' << kHeight
    << "\" font-family=\"sans-serif\" font-size=\"13\">\n";
  o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o << "<text x=\"" << kWidth / 2 << "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">"
    << escape(plot.title) << "</text>\n";
  write_grid(o, ax);
  const double left = kPlotLeft, right = kPlotRight, top = kPlotTop, bottom = kPlotBottom;
  o << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << right - left
    << "\" height=\"" << bottom - top << "\" fill=\"none\" stroke=\"black\"/>\n";
  o << "<text x=\"" << (left + right) / 2 << "\" y=\"" << kHeight - 20
    << "\" text-anchor=\"middle\">" << escape(plot.x_label) << "</text>\n";
  o << "<text transform=\"translate(24," << (top + bottom) / 2
    << ") rotate(-90)\" text-anchor=\"middle\">" << escape(plot.y_label) << "</text>\n";

  write_series(o, ax, plot, ymin);
  write_legend(o, plot);
  o << "</svg>\n";
  return o.str();
}

}  // namespace sss::app
