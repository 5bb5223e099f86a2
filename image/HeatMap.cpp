#include "image/HeatMap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace sss::image {

namespace {

// Viridis sampled at t = 0, 0.1, …, 1 (8-bit sRGB), as published with matplotlib's
// colour map and the R package viridis (viridis(11)).
constexpr std::array<std::array<int, 3>, 11> kViridis = {{
    {68, 1, 84},    {72, 37, 118},  {65, 68, 135},  {53, 96, 141},   {42, 120, 142}, {33, 144, 140},
    {34, 168, 132}, {67, 191, 113}, {122, 209, 81}, {187, 223, 39},  {253, 231, 37},
}};

struct Glyph {
  char c;
  const char* rows[kGlyphHeight];  // '#' = ink
};

// A 5×7 font drawn for this file (digits after the classic 5×7 LED/LCD matrix shapes).
constexpr Glyph kFont[] = {
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {'e', {".....", ".....", ".###.", "#...#", "#####", "#....", ".###."}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {'+', {".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."}},
    {'%', {"##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##"}},
    {' ', {".....", ".....", ".....", ".....", ".....", ".....", "....."}},
};

const Glyph* find_glyph(char c) {
  for (const Glyph& g : kFont)
    if (g.c == c) return &g;
  return nullptr;
}

void fill(Image& img, int x0, int y0, int w, int h, const Rgb& color) {
  for (int y = std::max(0, y0); y < std::min(img.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(img.width, x0 + w); ++x) {
      float* p = img.pixel(x, y);
      p[0] = color[0];
      p[1] = color[1];
      p[2] = color[2];
      p[3] = 1.0f;
    }
}

std::string strip_zeros(std::string s) {
  if (s.find('.') == std::string::npos) return s;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}


// The canvas of every map: black, the per-pixel colours at (0, 0) (mask 0: grey), the
// bar (`bar_colour` of t = 0 at its bottom row to t = 1 at its top) and the labelled
// ticks of the layout.
template <class PixelColour, class BarColour>
Image draw_map(const HeatMapLayout& l, const std::vector<float>& values,
               const std::vector<std::uint8_t>& mask, PixelColour pixel_colour,
               BarColour bar_colour) {
  const int width = l.image_width, height = l.image_height;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  if (values.size() != n || mask.size() != n)
    throw std::invalid_argument("heat map: values or mask do not match the image size");
  Image img(l.width, l.height);
  fill(img, 0, 0, l.width, l.height, kHeatMapBackground);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      fill(img, x, y, 1, 1, mask[i] ? pixel_colour(values[i]) : kHeatMapMasked);
    }
  for (int y = 0; y < l.bar_height; ++y) {
    const double t = l.bar_height > 1 ? double(l.bar_height - 1 - y) / (l.bar_height - 1) : 1.0;
    fill(img, l.bar_x, l.bar_y + y, l.bar_width, 1, bar_colour(t));
  }
  const int text_h = kGlyphHeight * l.scale;
  for (int i = 0; i < kHeatMapTicks; ++i) {
    fill(img, l.tick_x, l.tick_y[i], l.tick_length, l.scale, kHeatMapText);
    draw_text(img, l.label_x, l.tick_y[i] - text_h / 2, l.labels[i], l.scale, kHeatMapText);
  }
  return img;
}

// A signed quantity v per pixel through diverging(v / range) (NaN: kLogRatioInvalid), in a
// layout whose bar runs from -range to +range: the log-ratio map and the signed heat map.
Image draw_diverging_map(const HeatMapLayout& l, const std::vector<float>& values,
                         const std::vector<std::uint8_t>& mask) {
  const double range = l.max_value;
  return draw_map(
      l, values, mask, [&](float v) { return std::isnan(v) ? kLogRatioInvalid : diverging(v / range); },
      [](double t) { return diverging(2.0 * t - 1.0); });
}

}  // namespace

Rgb viridis(double t) {
  if (!(t > 0.0)) t = 0.0;
  t = std::min(t, 1.0);
  const double f = t * (kViridis.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(f), kViridis.size() - 2);
  const double u = f - static_cast<double>(i);
  Rgb out{};
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<float>(((1.0 - u) * kViridis[i][c] + u * kViridis[i + 1][c]) / 255.0);
  return out;
}

bool has_glyph(char c) { return find_glyph(c) != nullptr; }

int text_width(std::string_view text, int scale) {
  if (text.empty()) return 0;
  return (static_cast<int>(text.size()) * kGlyphAdvance - (kGlyphAdvance - kGlyphWidth)) * scale;
}

void draw_text(Image& img, int x, int y, std::string_view text, int scale, const Rgb& color) {
  if (scale < 1) throw std::invalid_argument("draw_text: scale must be >= 1");
  for (char c : text) {
    const Glyph* g = find_glyph(c);
    if (!g) throw std::invalid_argument(std::string("draw_text: no glyph for '") + c + "'");
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col)
        if (g->rows[row][col] == '#') fill(img, x + col * scale, y + row * scale, scale, scale, color);
    x += kGlyphAdvance * scale;
  }
}

std::string format_tick(double value) {
  if (value == 0.0 || !std::isfinite(value)) return "0";
  const double av = std::fabs(value);
  char buf[64];
  if (av >= 1e-3 && av < 1e5) {
    const int decimals = std::clamp(2 - static_cast<int>(std::floor(std::log10(av))), 0, 5);
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    return strip_zeros(buf);
  }
  std::snprintf(buf, sizeof buf, "%.2e", value);
  const std::string s = buf;
  const std::size_t e = s.find('e');
  return strip_zeros(s.substr(0, e)) + "e" + std::to_string(std::atoi(s.c_str() + e + 1));
}

HeatMapLayout heatmap_layout(int width, int height, double max_value) {
  if (!std::isfinite(max_value) || !(max_value > 0.0))
    throw std::invalid_argument("heat map: the scale maximum must be finite and > 0");
  return scale_bar_layout(width, height, 0.0, max_value, false);
}

HeatMapLayout scale_bar_layout(int width, int height, double min_value, double max_value,
                               bool signed_labels) {
  if (width < 1 || height < 1)
    throw std::invalid_argument("heat map: image size must be at least 1x1");
  if (!std::isfinite(min_value) || !std::isfinite(max_value) || !(min_value < max_value))
    throw std::invalid_argument("heat map: the scale's ends must be finite, bottom < top");
  HeatMapLayout l;
  l.image_width = width;
  l.image_height = height;
  l.min_value = min_value;
  l.max_value = max_value;
  const int s = std::clamp(height / 180, 1, 4);
  l.scale = s;
  const int pad = 4 * s, text_h = kGlyphHeight * s;
  const int margin = pad + text_h / 2 + 1;  // room for the top and bottom labels
  int label_w = 0;
  for (int i = 0; i < kHeatMapTicks; ++i) {
    const double f = double(i) / (kHeatMapTicks - 1);
    // The middle tick of a symmetric bar is exactly 0, not a rounding residue.
    double v = min_value + (max_value - min_value) * f;
    if (std::fabs(v) < 1e-12 * (max_value - min_value)) v = 0.0;
    l.tick_values[i] = v;
    l.labels[i] = (signed_labels && v > 0.0 ? "+" : "") + format_tick(v);
    label_w = std::max(label_w, text_width(l.labels[i], s));
  }
  // The tick marks sit on the bar's left, between it and the image: on its right, a mark
  // followed by a label read as a minus sign ("-0", "-4.63" on an unsigned bar).
  l.tick_length = 3 * s;
  l.tick_x = width + pad;
  l.bar_x = l.tick_x + l.tick_length;
  l.bar_width = 10 * s;
  l.label_x = l.bar_x + l.bar_width + 2 * s;
  l.width = l.label_x + label_w + pad;
  l.height = std::max(height, 40 * s + 2 * margin);
  l.bar_y = margin;
  l.bar_height = l.height - 2 * margin;
  for (int i = 0; i < kHeatMapTicks; ++i)
    l.tick_y[i] = l.bar_y + static_cast<int>(std::lround((l.bar_height - 1) *
                                                         (1.0 - double(i) / (kHeatMapTicks - 1))));
  return l;
}

Image render_heatmap(const std::vector<float>& error, const std::vector<std::uint8_t>& mask,
                     int width, int height, double max_value) {
  const HeatMapLayout l = heatmap_layout(width, height, max_value);
  return draw_map(l, error, mask, [&](float e) { return viridis(e / max_value); },
                  [](double t) { return viridis(t); });
}

double robust_scale(const std::vector<float>& values, const std::vector<std::uint8_t>& mask,
                    double quantile) {
  if (values.size() != mask.size())
    throw std::invalid_argument("heat map scale: the values and the mask differ in size");
  if (!(quantile >= 0.0 && quantile <= 1.0))
    throw std::invalid_argument("heat map scale: the quantile must be in [0, 1]");
  std::vector<float> v;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (mask[i] && std::isfinite(values[i])) v.push_back(std::fabs(values[i]));
  if (v.empty()) return 0.0;
  const auto nth = v.begin() + std::ptrdiff_t(quantile * double(v.size() - 1));
  std::nth_element(v.begin(), nth, v.end());
  return *nth;
}

std::vector<float> signed_pixel_errors(const Image& a, const Image& b) {
  (void)geometry_mask(a, b);  // throws on a size mismatch
  const std::size_t n = static_cast<std::size_t>(a.width) * a.height;
  std::vector<float> d(n);
  for (std::size_t i = 0; i < n; ++i) {
    float best = 0.0f;
    for (int c = 0; c < 3; ++c) {
      const float e = a.rgba[4 * i + c] - b.rgba[4 * i + c];
      if (std::fabs(e) > std::fabs(best) || std::isnan(e)) best = e;
      if (std::isnan(best)) break;
    }
    d[i] = best;
  }
  return d;
}

Image render_signed_heatmap(const std::vector<float>& difference,
                            const std::vector<std::uint8_t>& mask, int width, int height,
                            double max_value) {
  if (!std::isfinite(max_value) || !(max_value > 0.0))
    throw std::invalid_argument("heat map: the scale maximum must be finite and > 0");
  return draw_diverging_map(scale_bar_layout(width, height, -max_value, max_value, true), difference,
                            mask);
}

// ---- signed log ratio ----------------------------------------------------------------

Rgb diverging(double t) {
  if (std::isnan(t)) return kLogRatioEqual;
  t = std::clamp(t, -1.0, 1.0);
  const Rgb& end = t < 0.0 ? kLogRatioDarker : kLogRatioBrighter;
  const double u = std::fabs(t);
  Rgb out{};
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<float>((1.0 - u) * kLogRatioEqual[c] + u * end[c]);
  return out;
}

std::vector<float> log2_luminance_ratio(const Image& a, const Image& b, Encoding encoding) {
  const std::vector<std::uint8_t> mask = geometry_mask(a, b);  // throws on a size mismatch
  const std::size_t n = mask.size();
  // Luminance of linear values (NaN for a non-finite R, G or B; negative counts as 0).
  const auto luminance = [&](const Image& img, std::size_t i) {
    const float* p = &img.rgba[4 * i];
    double rgb[3];
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(p[c])) return std::numeric_limits<double>::quiet_NaN();
      rgb[c] = encoding == Encoding::Display ? srgb_decode(p[c]) : p[c];
    }
    return std::max(0.0, 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]);
  };
  std::vector<double> ya(n), yb(n);
  double sum_a = 0.0, sum_b = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    ya[i] = luminance(a, i);
    yb[i] = luminance(b, i);
    if (mask[i] && std::isfinite(ya[i]) && std::isfinite(yb[i])) {
      sum_a += ya[i];
      sum_b += yb[i];
      ++count;
    }
  }
  const double level = count > 0 ? std::max(sum_a, sum_b) / double(count) : 0.0;
  double floor = kLogRatioFloor * level;
  if (!(floor >= double(std::numeric_limits<float>::min())))
    floor = double(std::numeric_limits<float>::min());
  std::vector<float> r(n);
  for (std::size_t i = 0; i < n; ++i)
    r[i] = std::isnan(ya[i]) || std::isnan(yb[i])
               ? std::numeric_limits<float>::quiet_NaN()
               : static_cast<float>(std::log2(std::max(ya[i], floor) / std::max(yb[i], floor)));
  return r;
}

LogRatioStats log_ratio_stats(const std::vector<float>& log2_ratio,
                              const std::vector<std::uint8_t>& mask, double tolerance) {
  if (log2_ratio.size() != mask.size())
    throw std::invalid_argument("log ratio statistics: the ratios and the mask differ in size");
  if (!std::isfinite(tolerance) || !(tolerance > 0.0))
    throw std::invalid_argument("log ratio statistics: the tolerance must be finite and > 0");
  LogRatioStats s;
  s.tolerance = tolerance;
  const double limit = std::log2(1.0 + tolerance);
  double sum = 0.0, sum_abs = 0.0;
  std::size_t brighter = 0, darker = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    const double r = log2_ratio[i];
    if (!std::isfinite(r)) {
      ++s.non_finite;
      continue;
    }
    ++s.compared;
    sum += r;
    sum_abs += std::fabs(r);
    brighter += r > limit;
    darker += r < -limit;
  }
  if (s.compared > 0) {
    const double n = double(s.compared);
    s.mean_log2 = sum / n;
    s.mean_abs_log2 = sum_abs / n;
    s.fraction_brighter = double(brighter) / n;
    s.fraction_darker = double(darker) / n;
  }
  return s;
}

HeatMapLayout log_ratio_layout(int width, int height, double range_stops) {
  if (!std::isfinite(range_stops) || !(range_stops > 0.0))
    throw std::invalid_argument("log ratio map: the range must be a finite number of stops > 0");
  return scale_bar_layout(width, height, -range_stops, range_stops, true);
}

Image render_log_ratio_map(const std::vector<float>& log2_ratio,
                           const std::vector<std::uint8_t>& mask, int width, int height,
                           double range_stops) {
  return draw_diverging_map(log_ratio_layout(width, height, range_stops), log2_ratio, mask);
}

}  // namespace sss::image
