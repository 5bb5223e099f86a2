// Error heat maps: a per-pixel error image mapped through a colour map, with a labelled
// colour bar drawn beside it. Two kinds, one layout:
//   - the absolute error max_c |a − b| through viridis (sss-compare --heatmap);
//   - the signed log ratio log2(A/B) of the luminances through a diverging blue-white-red
//     map (sss-compare --log-ratio; the viewer's Compare panel), below.
//
// The colour map is viridis (van der Walt and Smith 2015, the default colour map of
// matplotlib 2.0: "A Better Default Colormap for Matplotlib", SciPy 2015), approximated by
// linear interpolation, in sRGB, between its 11 published samples at t = 0, 0.1, …, 1. It
// increases monotonically in lightness, so larger errors always look brighter, and it
// stays readable in grey and for the common colour-vision deficiencies.
//
// Layout (all in pixels, s = the font scale, 1..4 with the image height):
//
//   +---------------------+ pad   +-----+   label
//   | the error image,    |     --| bar |   0.02
//   | pixel (x, y) of the |       |     |
//   | inputs at (x, y)    |     --|     |   0.01
//   +---------------------+       |     |
//     (black below when the     --|     |   0
//      bar is taller)      tick   +-----+
//
// The bar runs from the scale's maximum at its top row to 0 at its bottom row with five
// ticks (0, ¼, ½, ¾, 1 of the maximum) labelled in a built-in 5×7 bitmap font. The tick
// marks are on the bar's left, so that no mark stands before a label as a minus sign.
// Errors above the maximum take the top colour; pixels outside the mask are dark grey; the
// canvas around is black.
#pragma once

#include "image/Image.h"
#include "image/Metrics.h"

#include <array>
#include <cstddef>
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
  int tick_x = 0, tick_length = 0;  // tick marks from tick_x rightwards, up to the bar
  int label_x = 0;                  // labels' left edge
  double min_value = 0.0, max_value = 1.0;  // the bar's bottom and top row
  std::array<double, kHeatMapTicks> tick_values{};
  std::array<int, kHeatMapTicks> tick_y{};  // the bar row of each tick
  std::array<std::string, kHeatMapTicks> labels;
};

// Throws std::invalid_argument unless width, height >= 1 and max_value is finite and > 0.
HeatMapLayout heatmap_layout(int width, int height, double max_value);
// The same layout for a bar from min_value (bottom) to max_value (top), ticks at 0, ¼, ½,
// ¾, 1 of the way up; with `signed_labels` positive ticks read "+0.5" (a signed quantity,
// where "0.5" alone could be a magnitude). Throws std::invalid_argument unless width,
// height >= 1 and both ends are finite with min_value < max_value.
HeatMapLayout scale_bar_layout(int width, int height, double min_value, double max_value,
                               bool signed_labels);

// `error` and `mask` are row-major width×height (mask 0: not compared, drawn grey).
Image render_heatmap(const std::vector<float>& error, const std::vector<std::uint8_t>& mask,
                     int width, int height, double max_value);

// A robust top for a map's scale: the `quantile` (default the 99th percentile) of |value|
// over the mask's pixels with a finite value, so that a few silhouette or shadow-edge
// pixels do not turn the rest of the map dark (they take the top colour); 0 when there is
// no such pixel. Throws std::invalid_argument if the sizes differ or the quantile is
// outside [0, 1]. The viewer's Compare panel and `sss-compare --heatmap` use it.
inline constexpr double kHeatMapQuantile = 0.99;
double robust_scale(const std::vector<float>& values, const std::vector<std::uint8_t>& mask,
                    double quantile = kHeatMapQuantile);

// The signed error: per pixel, a_c − b_c of the channel c with the largest |a_c − b_c|
// (so |d| is pixel_errors()' e; NaN where a value is not finite). d > 0: A above the
// reference. Throws std::invalid_argument if the sizes differ.
std::vector<float> signed_pixel_errors(const Image& a, const Image& b);
// d through the diverging map below (blue: A below B, white: equal, red: A above), from
// −max_value to +max_value, with a signed colour bar (sss-compare --heatmap-signed).
Image render_signed_heatmap(const std::vector<float>& difference,
                            const std::vector<std::uint8_t>& mask, int width, int height,
                            double max_value);

// ---- Signed log-ratio maps --------------------------------------------------------
//
// Per pixel, r = log2(Y_a / Y_b): how many stops A is brighter (r > 0) or darker (r < 0)
// than the reference B; r = 1 is twice as bright, r = −1 half. Y is the luminance
// 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709) of linear values: one signed number per
// pixel, weighted as the eye weights brightness, rather than a ratio per channel, whose
// three signs could disagree. So a hue error at equal luminance does not show here (the
// absolute map shows it). Display-encoded images (Encoding::Display, PNG) are first
// linearized with the sRGB decode, so that the ratio is one of light, not of 8-bit codes
// (a code ratio of 2 is a light ratio of about 4.6); the tonemap's curve is not undone, so
// between two tonemapped images a highlight's ratio is compressed. Linear images (EXR)
// are taken as they are.
//
// What is drawn where the ratio is not a plain one:
//   - no geometry in A or in B (image::geometry_mask 0): background, kHeatMapMasked grey;
//   - a negative luminance (not a radiance) counts as 0;
//   - both luminances are raised to a floor f = kLogRatioFloor × the larger of the two
//     images' mean luminance over the compared pixels (f = the smallest normal float if
//     both means are 0). So a pixel black in both is equal (r = 0, white); one black in
//     one image only is ±log2(Y / f), usually past the range (the saturated end, which is
//     what it is: darker or brighter without bound); and noise far below the images'
//     level cannot swing the ratio to ±∞;
//   - a non-finite R, G or B in A or in B: r is NaN, drawn kLogRatioInvalid (green, off
//     the blue-white-red ramp) and left out of the statistics.
//
// The colour map (written for this project): t = r / range, clamped to [−1, 1]; white at
// t = 0, kLogRatioDarker (blue) at −1, kLogRatioBrighter (red) at +1, linear in display
// values between white and each end. The two ends have the same luma (to 0.002), so the
// map is symmetric: a pixel k stops brighter is exactly as far from white as one k stops
// darker, and the lightness falls strictly with |t| on both sides.

inline constexpr Rgb kLogRatioDarker = {0.10f, 0.23f, 0.85f};    // A darker: blue
inline constexpr Rgb kLogRatioBrighter = {0.80f, 0.10f, 0.10f};  // A brighter: red
inline constexpr Rgb kLogRatioEqual = {1.0f, 1.0f, 1.0f};
inline constexpr Rgb kLogRatioInvalid = {0.0f, 0.75f, 0.0f};  // a non-finite input
inline constexpr double kDefaultLogRange = 1.0;  // stops: the map saturates at 2x and 1/2
inline constexpr double kLogRatioFloor = 1e-3;   // of the larger mean luminance
inline constexpr double kLogRatioTolerance = 0.05;  // the statistics' "beyond ±5%"

// The diverging colour map at t in [−1, 1] (clamped; NaN gives white).
Rgb diverging(double t);

// r per pixel, row-major (NaN where A or B has a non-finite R, G or B). Every pixel gets a
// value; the mask says which are compared. Throws std::invalid_argument if the sizes differ.
std::vector<float> log2_luminance_ratio(const Image& a, const Image& b, Encoding encoding);

// The statistics of r over the mask's pixels with a finite r. "Beyond ±tolerance" is
// symmetric in stops: r > log2(1 + tolerance) is brighter (A > 1.05 B by default), r <
// −log2(1 + tolerance) darker (A < B / 1.05), so a pixel and its swapped pair count alike.
struct LogRatioStats {
  std::size_t compared = 0;    // mask pixels with a finite r
  std::size_t non_finite = 0;  // mask pixels with a NaN r
  double mean_log2 = 0.0;      // the mean r: the overall bias, in stops
  double mean_abs_log2 = 0.0;  // the mean |r|
  double tolerance = kLogRatioTolerance;
  double fraction_brighter = 0.0, fraction_darker = 0.0;  // of `compared`
  double fraction_beyond() const { return fraction_brighter + fraction_darker; }
};
// Throws std::invalid_argument if the sizes differ or the tolerance is not finite and > 0.
LogRatioStats log_ratio_stats(const std::vector<float>& log2_ratio,
                              const std::vector<std::uint8_t>& mask,
                              double tolerance = kLogRatioTolerance);

// The bar of a log-ratio map: from −range (bottom, blue) to +range (top, red), ticks at
// −range, −range/2, 0, +range/2, +range in stops, signed. Throws std::invalid_argument
// unless range_stops is finite and > 0 (and as heatmap_layout for the size).
HeatMapLayout log_ratio_layout(int width, int height, double range_stops);

// The map of r through diverging(r / range_stops) with its colour bar, in the heat map's
// layout (above). `mask` 0: grey.
Image render_log_ratio_map(const std::vector<float>& log2_ratio,
                           const std::vector<std::uint8_t>& mask, int width, int height,
                           double range_stops = kDefaultLogRange);

}  // namespace sss::image
