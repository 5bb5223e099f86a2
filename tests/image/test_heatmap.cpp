// Heat maps (image/HeatMap.h): the colour map's published end points and order,
// the built-in font, tick labels, and the rendered image: its size, the error pixels in
// place, the masked pixels grey, and a colour bar with ticks and labels beside it.
#include "image/HeatMap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <stdexcept>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace sss::image;

namespace {

Rgb rgb8(int r, int g, int b) { return {r / 255.0f, g / 255.0f, b / 255.0f}; }

void expect_rgb(const float* p, const Rgb& c, const char* what) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(p[i], c[i], 1e-6f) << what << " channel " << i;
}

double luma8(const Rgb& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

bool is_text(const float* p) { return p[0] == 1.0f && p[1] == 1.0f && p[2] == 1.0f; }

}  // namespace

TEST(HeatMap, ViridisEndPointsAndOrder) {
  const Rgb lo = viridis(0.0), mid = viridis(0.5), hi = viridis(1.0);
  expect_rgb(lo.data(), rgb8(68, 1, 84), "t=0");      // #440154
  expect_rgb(mid.data(), rgb8(33, 144, 140), "t=.5");  // #21908C
  expect_rgb(hi.data(), rgb8(253, 231, 37), "t=1");   // #FDE725
  // Perceptually ordered: the luma rises strictly from 0 to 1.
  double previous = -1.0;
  for (int i = 0; i <= 200; ++i) {
    const double l = luma8(viridis(i / 200.0));
    EXPECT_GT(l, previous) << i;
    previous = l;
  }
  EXPECT_EQ(viridis(-3.0), lo);
  EXPECT_EQ(viridis(7.0), hi);
  EXPECT_EQ(viridis(std::numeric_limits<double>::quiet_NaN()), lo);
}

TEST(HeatMap, FontHasEveryGlyphItNeedsAndTheyDiffer) {
  const std::string chars = "0123456789.e-+%";
  std::set<std::vector<float>> shapes;
  for (char c : chars) {
    ASSERT_TRUE(has_glyph(c)) << c;
    Image img(kGlyphWidth, kGlyphHeight);
    draw_text(img, 0, 0, std::string(1, c), 1, {1.0f, 1.0f, 1.0f});
    int ink = 0;
    for (std::size_t i = 0; i < img.rgba.size(); i += 4) ink += img.rgba[i] > 0.5f;
    EXPECT_GT(ink, 0) << c;
    shapes.insert(img.rgba);
  }
  EXPECT_EQ(shapes.size(), chars.size());  // no two glyphs alike
  EXPECT_TRUE(has_glyph(' '));
  EXPECT_FALSE(has_glyph('x'));
  Image img(20, 10);
  EXPECT_THROW(draw_text(img, 0, 0, "1x", 1, {1, 1, 1}), std::invalid_argument);
  EXPECT_EQ(text_width("", 1), 0);
  EXPECT_EQ(text_width("1", 1), 5);
  EXPECT_EQ(text_width("12", 1), 11);
  EXPECT_EQ(text_width("12", 3), 33);
}

TEST(HeatMap, TextIsScaledAndClipped) {
  Image img(12, 16);
  draw_text(img, 0, 0, "-", 2, {1.0f, 0.0f, 0.0f});  // '-' is row 3, columns 0..4
  EXPECT_EQ(img.pixel(0, 6)[0], 1.0f);
  EXPECT_EQ(img.pixel(9, 7)[0], 1.0f);
  EXPECT_EQ(img.pixel(10, 6)[0], 0.0f);
  EXPECT_EQ(img.pixel(0, 5)[0], 0.0f);
  EXPECT_EQ(img.pixel(0, 8)[0], 0.0f);
  EXPECT_NO_THROW(draw_text(img, -7, -3, "88", 3, {1, 1, 1}));  // partly outside
  EXPECT_NO_THROW(draw_text(img, 100, 100, "8", 1, {1, 1, 1}));
}

TEST(HeatMap, TickLabels) {
  EXPECT_EQ(format_tick(0.0), "0");
  EXPECT_EQ(format_tick(0.5), "0.5");
  EXPECT_EQ(format_tick(0.25), "0.25");
  EXPECT_EQ(format_tick(0.0125), "0.0125");
  EXPECT_EQ(format_tick(0.123456), "0.123");
  EXPECT_EQ(format_tick(1.0), "1");
  EXPECT_EQ(format_tick(37.5), "37.5");
  EXPECT_EQ(format_tick(1234.0), "1234");
  EXPECT_EQ(format_tick(2.5e-5), "2.5e-5");
  EXPECT_EQ(format_tick(1.0e-4), "1e-4");
  EXPECT_EQ(format_tick(1.5e7), "1.5e7");
  EXPECT_EQ(format_tick(-0.5), "-0.5");
  for (double v : {0.0, 1e-9, 3.3e-4, 0.07, 1.0, 99999.0, 2e12})
    for (char c : format_tick(v)) EXPECT_TRUE(has_glyph(c)) << v << " " << c;
}

TEST(HeatMap, LayoutPutsTheBarBesideTheImage) {
  for (auto [w, h] : {std::pair{8, 6}, {64, 48}, {640, 360}, {300, 1000}}) {
    const HeatMapLayout l = heatmap_layout(w, h, 0.2);
    EXPECT_EQ(l.image_width, w);
    EXPECT_EQ(l.image_height, h);
    EXPECT_GE(l.height, h);
    EXPECT_GT(l.bar_x, w);
    EXPECT_GT(l.label_x, l.bar_x + l.bar_width);
    EXPECT_LE(l.label_x + text_width(l.labels[2], l.scale), l.width);
    EXPECT_GE(l.bar_y, 0);
    EXPECT_LE(l.bar_y + l.bar_height, l.height);
    EXPECT_GE(l.bar_height, 40 * l.scale);
    EXPECT_EQ(l.labels[0], "0");
    EXPECT_EQ(l.labels[2], "0.1");
    EXPECT_EQ(l.labels[4], "0.2");
    EXPECT_EQ(l.tick_y[4], l.bar_y);                     // the maximum at the top
    EXPECT_EQ(l.tick_y[0], l.bar_y + l.bar_height - 1);  // 0 at the bottom
  }
  EXPECT_EQ(heatmap_layout(640, 360, 1.0).scale, 2);
  EXPECT_THROW(heatmap_layout(0, 5, 1.0), std::invalid_argument);
  EXPECT_THROW(heatmap_layout(5, 5, 0.0), std::invalid_argument);
  EXPECT_THROW(heatmap_layout(5, 5, std::numeric_limits<double>::infinity()), std::invalid_argument);
}

TEST(HeatMap, RendersErrorsMaskAndColourBar) {
  const int w = 32, h = 24;
  const double top = 0.4;
  std::vector<float> error(static_cast<std::size_t>(w) * h);
  std::vector<std::uint8_t> mask(error.size(), 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) error[static_cast<std::size_t>(y) * w + x] = 0.01f * x;
  for (int x = 0; x < w; ++x) mask[x] = 0;  // top row: background
  error[static_cast<std::size_t>(5) * w + 3] = 9.0f;  // above the scale
  const Image img = render_heatmap(error, mask, w, h, top);
  const HeatMapLayout l = heatmap_layout(w, h, top);
  ASSERT_EQ(img.width, l.width);
  ASSERT_EQ(img.height, l.height);
  ASSERT_GT(img.width, w);

  // The error image, pixel for pixel where the inputs have it.
  expect_rgb(img.pixel(10, 0), kHeatMapMasked, "masked");
  expect_rgb(img.pixel(0, 3), viridis(0.0), "zero error");
  expect_rgb(img.pixel(20, 7), viridis(0.01f * 20 / top), "error 0.2");
  expect_rgb(img.pixel(3, 5), viridis(1.0), "clamped");
  // Black canvas beside the image and (here, as the bar is taller) below it.
  ASSERT_GT(l.height, h);
  expect_rgb(img.pixel(2, h + 1), kHeatMapBackground, "below");
  expect_rgb(img.pixel(w + 1, 1), kHeatMapBackground, "gap");

  // The bar: top row the maximum's colour, bottom row 0's, the luma falling in between.
  const int bx = l.bar_x + l.bar_width / 2;
  expect_rgb(img.pixel(bx, l.bar_y), viridis(1.0), "bar top");
  expect_rgb(img.pixel(bx, l.bar_y + l.bar_height - 1), viridis(0.0), "bar bottom");
  for (int y = l.bar_y + 1; y < l.bar_y + l.bar_height; ++y) {
    const float* p = img.pixel(bx, y);
    const float* q = img.pixel(bx, y - 1);
    EXPECT_LT(luma8({p[0], p[1], p[2]}), luma8({q[0], q[1], q[2]})) << y;
  }
  // Ticks and labels: white marks at every tick, and ink in each label's box.
  for (int i = 0; i < kHeatMapTicks; ++i) {
    EXPECT_TRUE(is_text(img.pixel(l.tick_x, l.tick_y[i]))) << i;
    int ink = 0;
    const int ty = l.tick_y[i] - kGlyphHeight * l.scale / 2;
    for (int y = ty; y < ty + kGlyphHeight * l.scale; ++y)
      for (int x = l.label_x; x < l.label_x + text_width(l.labels[i], l.scale); ++x)
        ink += is_text(img.pixel(x, y));
    EXPECT_GT(ink, 4) << l.labels[i];
    // Between the bar and the label, nothing: a tick mark there read as a minus sign on
    // an unsigned bar ("-0", "-4.63"; issue 20). The marks are on the bar's other side.
    EXPECT_LT(l.tick_x + l.tick_length, l.bar_x + 1) << i;
    for (int x = l.bar_x + l.bar_width; x < l.label_x; ++x)
      for (int dy = 0; dy < l.scale; ++dy)
        expect_rgb(img.pixel(x, l.tick_y[i] + dy), kHeatMapBackground, "before a label");
  }
  // Nothing but the canvas, the image, the bar and white ink.
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) ASSERT_EQ(img.rgba[i], 1.0f);

  EXPECT_THROW(render_heatmap(error, mask, w + 1, h, top), std::invalid_argument);
}

TEST(HeatMap, SurvivesPngRoundTrip) {
  std::vector<float> error(40 * 30, 0.25f);
  std::vector<std::uint8_t> mask(error.size(), 1);
  const Image img = render_heatmap(error, mask, 40, 30, 0.5);
  const fs::path p = fs::temp_directory_path() / ("sss-heatmap-" + std::to_string(::getpid()) + ".png");
  write_png(p.string(), img);
  auto back = read_image(p.string());
  fs::remove(p);
  ASSERT_TRUE(std::holds_alternative<Image>(back));
  const Image& b = std::get<Image>(back);
  ASSERT_EQ(b.width, img.width);
  ASSERT_EQ(b.height, img.height);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(b.pixel(5, 5)[c], viridis(0.5)[c], 0.5f / 255 + 1e-6f);
}

namespace sss::image {
namespace {

// The robust top: the 99th percentile of |value| over the mask's finite values, so one
// spike does not set it (index floor(0.99 (n - 1)) of the sorted values).
TEST(HeatMapScale, NinetyNinthPercentileOfTheMaskedValues) {
  std::vector<float> v(200);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = (i % 2 ? -1.0f : 1.0f) * float(i + 1) / 200.0f;
  std::vector<std::uint8_t> mask(v.size(), 1);
  v[0] = 1000.0f;  // a spike
  // |v| sorted: 0.01 .. 1 (199 values) and the spike; floor(0.99 * 199) = 197 -> 0.995.
  EXPECT_FLOAT_EQ(float(robust_scale(v, mask)), 0.995f);
  EXPECT_FLOAT_EQ(float(robust_scale(v, mask, 1.0)), 1000.0f);
  v[5] = std::numeric_limits<float>::quiet_NaN();  // left out, as a masked pixel is
  mask[7] = 0;
  EXPECT_GT(robust_scale(v, mask), 0.9);
  EXPECT_EQ(robust_scale(v, std::vector<std::uint8_t>(v.size(), 0)), 0.0);
  EXPECT_THROW(robust_scale(v, std::vector<std::uint8_t>(3, 1)), std::invalid_argument);
  EXPECT_THROW(robust_scale(v, mask, 1.5), std::invalid_argument);
}

// The signed error keeps the sign of the channel with the largest |a - b|.
TEST(HeatMapScale, SignedErrorIsTheWorstChannelsDifference) {
  Image a(2, 1), b(2, 1);
  const float pa[8] = {0.5f, 0.2f, 0.9f, 1, 0.1f, 0.4f, 0.4f, 1};
  const float pb[8] = {0.4f, 0.6f, 0.9f, 1, 0.1f, 0.1f, 0.4f, 1};
  std::copy(pa, pa + 8, a.rgba.begin());
  std::copy(pb, pb + 8, b.rgba.begin());
  const std::vector<float> d = signed_pixel_errors(a, b);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_FLOAT_EQ(d[0], 0.2f - 0.6f);  // green, A below
  EXPECT_FLOAT_EQ(d[1], 0.4f - 0.1f);  // green, A above
  const std::vector<float> e = pixel_errors(a, b);
  for (int i = 0; i < 2; ++i) EXPECT_FLOAT_EQ(std::fabs(d[i]), e[i]);
  EXPECT_THROW(signed_pixel_errors(a, Image(3, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace sss::image
