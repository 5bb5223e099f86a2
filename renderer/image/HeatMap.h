// Error heat maps: a per-pixel error image mapped through a perceptually ordered colour
// map, with a labelled colour bar drawn beside it, for sss-compare --heatmap.
//
// The colour map is viridis (van der Walt and Smith 2015, the default colour map of
// matplotlib 2.0: "A Better Default Colormap for Matplotlib", SciPy 2015), approximated by
// linear interpolation, in sRGB, between its 11 published samples at t = 0, 0.1, …, 1. It
// increases monotonically in lightness, so larger errors always look brighter, and it
// stays readable in grey and for the common colour-vision deficiencies.
//
// Layout (all in pixels, s = the font scale, 1..4 with the image height):
//
//   +---------------------+ pad +-----+ tick label
//   | the error image,    |     | bar |-- 0.02
//   | pixel (x, y) of the |     |     |
//   | inputs at (x, y)    |     |     |-- 0.01
//   +---------------------+     |     |
//     (black below when the     |     |-- 0
//      bar is taller)           +-----+
//
// The bar runs from the scale's maximum at its top row to 0 at its bottom row with five
// ticks (0, ¼, ½, ¾, 1 of the maximum) labelled in a built-in 5×7 bitmap font. Errors
// above the maximum take the top colour; pixels outside the mask are dark grey; the
// canvas around is black.
#pragma once

#include "renderer/image/Image.h"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sss::image {

using Rgb = std::array<float, 3>;

inline constexpr Rgb kHeatMapMasked = {0.25f, 0.25f, 0.25f};
inline constexpr Rgb kHeatMapBackground = {0.0f, 0.0f, 0.0f};
inline constexpr Rgb kHeatMapText = {1.0f, 1.0f, 1.0f};
inline constexpr int kHeatMapTicks = 5;

// Viridis at t in [0, 1] (clamped; NaN gives the t = 0 colour), as display values.
Rgb viridis(double t);

// The built-in font: 5×7 glyphs for 0-9 . e - + % and space, advancing 6 columns. Throws
// std::invalid_argument for any other character.
inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;
bool has_glyph(char c);
int text_width(std::string_view text, int scale);  // the last glyph's gap not counted
// Draws `text` with its top-left corner at (x, y), each font pixel a scale×scale square;
// parts outside the image are clipped.
void draw_text(Image& img, int x, int y, std::string_view text, int scale, const Rgb& color);

// A short label for a tick value: 3 significant digits (or the whole integer part, up to
// 5 digits), trailing zeros dropped; scientific notation ("2.5e-5", "1.5e7") outside
// [0.001, 100000). Uses only glyphs of the font.
std::string format_tick(double value);

struct HeatMapLayout {
  int image_width = 0, image_height = 0;  // the error image, at (0, 0)
  int width = 0, height = 0;              // the whole canvas
  int scale = 1;                          // font scale
  int bar_x = 0, bar_y = 0, bar_width = 0, bar_height = 0;
  int tick_x = 0, tick_length = 0;  // tick marks from tick_x, rightwards
  int label_x = 0;                  // labels' left edge
  double max_value = 1.0;
  std::array<double, kHeatMapTicks> tick_values{};
  std::array<int, kHeatMapTicks> tick_y{};  // the bar row of each tick
  std::array<std::string, kHeatMapTicks> labels;
};

// Throws std::invalid_argument unless width, height >= 1 and max_value is finite and > 0.
HeatMapLayout heatmap_layout(int width, int height, double max_value);

// `error` and `mask` are row-major width×height (mask 0: not compared, drawn grey).
Image render_heatmap(const std::vector<float>& error, const std::vector<std::uint8_t>& mask,
                     int width, int height, double max_value);

}  // namespace sss::image
