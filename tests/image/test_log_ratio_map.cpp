// Signed log-ratio maps (image/HeatMap.h): the diverging colour map's ends and
// symmetry, r = log2(Y_a / Y_b) from its definition (luminance weights, sRGB decode of
// display values, the floor, the guards), the statistics, and the rendered map: a half
// twice as bright at the red end, equal pixels white, background grey, the bar and its
// signed labels. Every expected value is worked out here from the definitions.
#include "image/HeatMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>
#include <stdexcept>

using namespace sss::image;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

double luma(const Rgb& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

void expect_rgb(const float* p, const Rgb& c, const std::string& what) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(p[i], c[i], 1e-6f) << what << " channel " << i;
}

void set(Image& img, int x, int y, float r, float g, float b, float a = 1.0f) {
  float* p = img.pixel(x, y);
  p[0] = r;
  p[1] = g;
  p[2] = b;
  p[3] = a;
}

// B: a gradient of linear values with alpha 1; A: B times `k` on the left half.
Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) set(img, x, y, 0.1f + 0.01f * x, 0.2f + 0.01f * y, 0.3f);
  return img;
}

Image scaled_left_half(const Image& b, float k) {
  Image a = b;
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width / 2; ++x)
      for (int c = 0; c < 3; ++c) a.pixel(x, y)[c] *= k;
  return a;
}

}  // namespace

TEST(LogRatioMap, DivergingMapIsWhiteAtZeroAndSymmetric) {
  expect_rgb(diverging(0.0).data(), kLogRatioEqual, "t=0");
  expect_rgb(diverging(1.0).data(), kLogRatioBrighter, "t=1");
  expect_rgb(diverging(-1.0).data(), kLogRatioDarker, "t=-1");
  EXPECT_EQ(diverging(5.0), diverging(1.0));  // clamped at ±range
  EXPECT_EQ(diverging(-5.0), diverging(-1.0));
  EXPECT_EQ(diverging(std::numeric_limits<double>::quiet_NaN()), kLogRatioEqual);
  // Linear between white and each end: half way is the average.
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(diverging(0.5)[c], 0.5 * (1.0 + kLogRatioBrighter[c]), 1e-6) << c;
    EXPECT_NEAR(diverging(-0.5)[c], 0.5 * (1.0 + kLogRatioDarker[c]), 1e-6) << c;
  }
  // The ends are a red and a blue of the same luma, so both halves fall alike and
  // strictly with |t|.
  EXPECT_GT(kLogRatioBrighter[0], kLogRatioBrighter[2]);
  EXPECT_GT(kLogRatioDarker[2], kLogRatioDarker[0]);
  EXPECT_NEAR(luma(kLogRatioBrighter), luma(kLogRatioDarker), 0.002);
  double previous = luma(diverging(0.0));
  for (int i = 1; i <= 100; ++i) {
    const double t = i / 100.0;
    const double up = luma(diverging(t)), down = luma(diverging(-t));
    EXPECT_LT(up, previous) << t;
    EXPECT_NEAR(up, down, 0.002) << t;
    previous = up;
  }
  // The invalid colour is off the ramp: no t gives it.
  for (int i = -100; i <= 100; ++i) EXPECT_NE(diverging(i / 100.0), kLogRatioInvalid);
}

TEST(LogRatioMap, RatioIsLog2OfTheLuminances) {
  const Image b = gradient(8, 4);
  const std::vector<float> r = log2_luminance_ratio(scaled_left_half(b, 2.0f), b, Encoding::Linear);
  ASSERT_EQ(r.size(), 32u);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) EXPECT_NEAR(r[y * 8 + x], x < 4 ? 1.0 : 0.0, 1e-6) << x << "," << y;
  const std::vector<float> half = log2_luminance_ratio(scaled_left_half(b, 0.5f), b, Encoding::Linear);
  EXPECT_NEAR(half[0], -1.0, 1e-6);
  // One channel changed: the ratio of the Rec. 709 luminances, not of that channel.
  Image a = b;
  a.pixel(1, 1)[0] *= 3.0f;
  const float* p = b.pixel(1, 1);
  const double expected = std::log2(luminance(3.0 * p[0], p[1], p[2]) / luminance(p[0], p[1], p[2]));
  EXPECT_NEAR(log2_luminance_ratio(a, b, Encoding::Linear)[9], expected, 1e-6);
  EXPECT_THROW(log2_luminance_ratio(gradient(8, 4), gradient(8, 5), Encoding::Linear),
               std::invalid_argument);
}

TEST(LogRatioMap, DisplayValuesAreLinearizedFirst) {
  // Codes whose light is 0.2 and 0.4: one stop, whatever the codes' own ratio (≈ 1.37).
  Image a(2, 1), b(2, 1);
  const float lo = srgb_encode(0.2f), hi = srgb_encode(0.4f);
  set(a, 0, 0, hi, hi, hi);
  set(b, 0, 0, lo, lo, lo);
  set(a, 1, 0, lo, lo, lo);
  set(b, 1, 0, lo, lo, lo);
  const std::vector<float> r = log2_luminance_ratio(a, b, Encoding::Display);
  EXPECT_NEAR(r[0], 1.0, 1e-5);
  EXPECT_EQ(r[1], 0.0f);
  // As linear values the same numbers are the codes' ratio.
  EXPECT_NEAR(log2_luminance_ratio(a, b, Encoding::Linear)[0], std::log2(double(hi) / lo), 1e-6);
}

TEST(LogRatioMap, GuardsForBlackNegativeAndNonFinitePixels) {
  // Four compared pixels: black in both, black in A, black in B, negative in A; and a NaN.
  Image a(5, 1), b(5, 1);
  set(a, 0, 0, 0, 0, 0);
  set(b, 0, 0, 0, 0, 0);
  set(a, 1, 0, 0, 0, 0);
  set(b, 1, 0, 1, 1, 1);
  set(a, 2, 0, 1, 1, 1);
  set(b, 2, 0, 0, 0, 0);
  set(a, 3, 0, -1, -1, -1);
  set(b, 3, 0, 0.5f, 0.5f, 0.5f);
  set(a, 4, 0, kNaN, 1, 1);
  set(b, 4, 0, 1, 1, 1);
  const std::vector<float> r = log2_luminance_ratio(a, b, Encoding::Linear);
  // Means over the finite compared pixels: A (0 + 0 + 1 + 0) / 4, B (0 + 1 + 0 + 0.5) / 4.
  const double f = kLogRatioFloor * std::max(1.0 / 4, 1.5 / 4);
  EXPECT_EQ(r[0], 0.0f);  // equal: white
  EXPECT_NEAR(r[1], std::log2(f / 1.0), 1e-5);
  EXPECT_NEAR(r[2], std::log2(1.0 / f), 1e-5);
  EXPECT_NEAR(r[3], std::log2(f / 0.5), 1e-5);  // a negative luminance is 0
  EXPECT_TRUE(std::isnan(r[4]));
  // Swapping A and B negates every finite ratio, the floored ones included.
  const std::vector<float> swapped = log2_luminance_ratio(b, a, Encoding::Linear);
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(swapped[i], -r[i]) << i;
  // All black: every pixel equal, no division by zero.
  const std::vector<float> black = log2_luminance_ratio(Image(3, 3), Image(3, 3), Encoding::Linear);
  for (float v : black) EXPECT_EQ(v, 0.0f);
}

TEST(LogRatioMap, StatisticsOverTheMask) {
  // r: +1 (2x), 0, log2(1.04), log2(1.06), −log2(1.06), a NaN, and a masked +5.
  const std::vector<float> r = {1.0f, 0.0f, float(std::log2(1.04)), float(std::log2(1.06)),
                                float(-std::log2(1.06)), kNaN, 5.0f};
  const std::vector<std::uint8_t> mask = {1, 1, 1, 1, 1, 1, 0};
  const LogRatioStats s = log_ratio_stats(r, mask);
  EXPECT_EQ(s.compared, 5u);
  EXPECT_EQ(s.non_finite, 1u);
  EXPECT_NEAR(s.mean_log2, (1.0 + std::log2(1.04)) / 5, 1e-6);
  EXPECT_NEAR(s.mean_abs_log2, (1.0 + std::log2(1.04) + 2 * std::log2(1.06)) / 5, 1e-6);
  EXPECT_DOUBLE_EQ(s.fraction_brighter, 2.0 / 5);  // 2x and 1.06x; 1.04x is within 5%
  EXPECT_DOUBLE_EQ(s.fraction_darker, 1.0 / 5);
  EXPECT_DOUBLE_EQ(s.fraction_beyond(), 3.0 / 5);
  EXPECT_DOUBLE_EQ(log_ratio_stats(r, mask, 1.5).fraction_brighter, 0.0);  // 2x is within 150%
  EXPECT_THROW(log_ratio_stats(r, std::vector<std::uint8_t>(3, 1)), std::invalid_argument);
  EXPECT_THROW(log_ratio_stats(r, mask, 0.0), std::invalid_argument);
  const LogRatioStats none = log_ratio_stats({kNaN}, {1});
  EXPECT_EQ(none.compared, 0u);
  EXPECT_EQ(none.mean_log2, 0.0);
}

TEST(LogRatioMap, ColourBarIsSignedAndSymmetric) {
  const HeatMapLayout l = log_ratio_layout(64, 48, 1.0);
  const std::array<std::string, kHeatMapTicks> one = {"-1", "-0.5", "0", "+0.5", "+1"};
  EXPECT_EQ(l.labels, one);
  EXPECT_EQ(l.min_value, -1.0);
  EXPECT_EQ(l.max_value, 1.0);
  EXPECT_EQ(l.tick_values[2], 0.0);
  EXPECT_EQ(l.tick_y[4], l.bar_y);                     // +range at the top
  EXPECT_EQ(l.tick_y[0], l.bar_y + l.bar_height - 1);  // −range at the bottom
  const std::array<std::string, kHeatMapTicks> two = {"-2", "-1", "0", "+1", "+2"};
  EXPECT_EQ(log_ratio_layout(64, 48, 2.0).labels, two);
  const std::array<std::string, kHeatMapTicks> small = {"-0.3", "-0.15", "0", "+0.15", "+0.3"};
  EXPECT_EQ(log_ratio_layout(64, 48, 0.3).labels, small);
  // The labels fit on the canvas, the widest ("-0.5") included.
  for (const std::string& label : l.labels) EXPECT_LE(l.label_x + text_width(label, l.scale), l.width);
  for (double bad : {0.0, -1.0, double(kNaN), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(log_ratio_layout(64, 48, bad), std::invalid_argument) << bad;
  // The absolute heat map's layout is unchanged: unsigned, from 0.
  EXPECT_EQ(heatmap_layout(64, 48, 0.2).labels[4], "0.2");
  EXPECT_EQ(heatmap_layout(64, 48, 0.2).min_value, 0.0);
}

TEST(LogRatioMap, RendersTwiceAsBrightAtTheRedEnd) {
  const int w = 32, h = 24;
  const Image b = gradient(w, h);
  Image a = scaled_left_half(b, 2.0f);
  set(a, 20, 3, kNaN, 0.5f, 0.5f);  // invalid
  const std::vector<float> r = log2_luminance_ratio(a, b, Encoding::Linear);
  std::vector<std::uint8_t> mask(r.size(), 1);
  for (int x = 0; x < w; ++x) mask[x] = 0;  // top row: background

  const Image img = render_log_ratio_map(r, mask, w, h);  // default range: 1 stop
  const HeatMapLayout l = log_ratio_layout(w, h, kDefaultLogRange);
  ASSERT_EQ(img.width, l.width);
  ASSERT_EQ(img.height, l.height);
  expect_rgb(img.pixel(3, 0), kHeatMapMasked, "background");
  expect_rgb(img.pixel(3, 5), kLogRatioBrighter, "2x: +1 stop, the red end");
  expect_rgb(img.pixel(w - 3, 5), kLogRatioEqual, "equal: white");
  expect_rgb(img.pixel(20, 3), kLogRatioInvalid, "non-finite");
  // With a range of 2 stops, 2x is half way to red.
  const Image wide = render_log_ratio_map(r, mask, w, h, 2.0);
  expect_rgb(wide.pixel(3, 5), diverging(0.5), "2x at range 2");
  // Half as bright is the blue end.
  const std::vector<float> darker = log2_luminance_ratio(scaled_left_half(b, 0.5f), b, Encoding::Linear);
  expect_rgb(render_log_ratio_map(darker, mask, w, h).pixel(3, 5), kLogRatioDarker, "1/2: blue");

  // The bar: red at the top, blue at the bottom, white in the middle row.
  const int bx = l.bar_x + l.bar_width / 2;
  expect_rgb(img.pixel(bx, l.bar_y), kLogRatioBrighter, "bar top");
  expect_rgb(img.pixel(bx, l.bar_y + l.bar_height - 1), kLogRatioDarker, "bar bottom");
  const float* mid = img.pixel(bx, l.tick_y[2]);
  for (int c = 0; c < 3; ++c) EXPECT_GT(mid[c], 0.95f) << "bar middle " << c;
  // Ticks and labels in white ink.
  for (int i = 0; i < kHeatMapTicks; ++i) {
    const float* t = img.pixel(l.tick_x, l.tick_y[i]);
    EXPECT_TRUE(t[0] == 1.0f && t[1] == 1.0f && t[2] == 1.0f) << i;
    int ink = 0;
    const int ty = l.tick_y[i] - kGlyphHeight * l.scale / 2;
    for (int y = ty; y < ty + kGlyphHeight * l.scale; ++y)
      for (int x = l.label_x; x < l.label_x + text_width(l.labels[i], l.scale); ++x)
        ink += img.pixel(x, y)[0] == 1.0f && img.pixel(x, y)[1] == 1.0f && img.pixel(x, y)[2] == 1.0f;
    EXPECT_GT(ink, 4) << l.labels[i];
  }
  EXPECT_THROW(render_log_ratio_map(r, mask, w + 1, h), std::invalid_argument);
  EXPECT_THROW(render_log_ratio_map(r, mask, w, h, 0.0), std::invalid_argument);
}
