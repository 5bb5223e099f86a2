// Image metrics (image/Metrics.h) against closed forms: identical images, constant
// offsets, scaled images, noise of known size, masking, and SSIM's own closed forms
// (flat images) and properties (1 for identical images, symmetric, < 1 for a contrast-
// reduced copy, negative for an inverted one).
#include "image/Metrics.h"
#include "image/Tonemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>

using namespace sss::image;

namespace {

constexpr double kC1 = (kSsimK1 * 1.0) * (kSsimK1 * 1.0), kC2 = (kSsimK2 * 1.0) * (kSsimK2 * 1.0);

Image make(int w, int h, const std::function<float(int, int, int)>& f, float alpha = 1.0f) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.pixel(x, y);
      for (int c = 0; c < 3; ++c) p[c] = f(x, y, c);
      p[3] = alpha;
    }
  return img;
}

Image flat(int w, int h, float v) {
  return make(w, h, [v](int, int, int) { return v; });
}

// A smooth, textured display image with values in [0.2, 0.7].
Image texture(int w, int h) {
  return make(w, h, [](int x, int y, int c) {
    return 0.45f + 0.25f * std::sin(0.7f * x + 0.3f * c) * std::cos(0.45f * y - 0.2f * c);
  });
}

template <class F>
Image map_image(const Image& in, F f) {
  Image out = in;
  for (std::size_t i = 0; i < out.rgba.size(); ++i)
    if (i % 4 != 3) out.rgba[i] = f(in.rgba[i], i);
  return out;
}

CompareOptions linear() {
  CompareOptions o;
  o.encoding = Encoding::Linear;
  return o;
}

}  // namespace

TEST(Metrics, IdenticalImagesAreExactlyEqual) {
  const Image b = texture(40, 30);
  for (const CompareOptions& o : {CompareOptions{}, linear()}) {
    const Metrics m = compare(b, b, o);
    EXPECT_EQ(m.total_pixels, 1200u);
    EXPECT_EQ(m.compared_pixels, 1200u);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.relative_rmse, 0.0);
    EXPECT_TRUE(std::isinf(m.psnr_db) && m.psnr_db > 0);
    EXPECT_EQ(m.max_abs_error, 0.0);
    EXPECT_EQ(m.pixels_over_threshold, 0u);
    EXPECT_EQ(m.fraction_over_threshold, 0.0);
    EXPECT_EQ(m.ssim, 1.0);  // bit-exact: the same sums on both sides
  }
}

TEST(Metrics, ConstantOffset) {
  const Image b = texture(32, 24);
  const float c = 0.03f;
  const Image a = map_image(b, [c](float v, std::size_t) { return v + c; });
  const Metrics m = compare(a, b);
  EXPECT_NEAR(m.rmse, c, 1e-6);
  EXPECT_NEAR(m.max_abs_error, c, 1e-6);
  EXPECT_NEAR(m.psnr_db, -20.0 * std::log10(c), 1e-3);  // peak 1
  EXPECT_EQ(m.peak, 1.0);
  EXPECT_EQ(m.fraction_over_threshold, 0.0);  // 0.03 < 0.05
  CompareOptions tight;
  tight.threshold = 0.02;
  EXPECT_EQ(compare(a, b, tight).fraction_over_threshold, 1.0);
  // Negative offsets are the same error.
  const Image a2 = map_image(b, [c](float v, std::size_t) { return v - c; });
  EXPECT_NEAR(compare(a2, b).rmse, c, 1e-6);
}

TEST(Metrics, RelativeRmseOfAScaledImageIsTheScaleError) {
  const Image b = texture(20, 20);
  for (float k : {0.5f, 0.9f, 1.02f, 2.0f}) {
    const Image a = map_image(b, [k](float v, std::size_t) { return k * v; });
    EXPECT_NEAR(compare(a, b).relative_rmse, std::fabs(k - 1.0f), 1e-6) << k;
    EXPECT_NEAR(compare(a, b, linear()).relative_rmse, std::fabs(k - 1.0f), 1e-6) << k;
  }
}

// The summed ratio is the bias per channel: k for a copy scaled by k, per channel, over the
// compared pixels only; a zero-mean perturbation leaves it at 1 while the RMSE grows.
TEST(Metrics, SumRatioIsEachChannelsScale) {
  const Image b = texture(20, 20);
  const float k[3] = {0.9f, 1.0f, 1.25f};
  Image a = map_image(b, [&](float v, std::size_t i) { return k[i % 4] * v; });
  a.pixel(0, 0)[3] = 0.0f;  // background in A: left out of both sums
  a.pixel(0, 0)[0] = 1e6f;
  const Metrics m = compare(a, b, linear());
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.sum_ratio[std::size_t(c)], k[c], 1e-6) << c;
  const Image wiggle = map_image(b, [](float v, std::size_t i) { return v + ((i / 4) % 2 ? 0.05f : -0.05f); });
  const Metrics w = compare(wiggle, b, linear());  // 400 pixels: as many + as -
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(w.sum_ratio[std::size_t(c)], 1.0, 1e-6) << c;
  EXPECT_GT(w.relative_rmse, 0.05);
  const Metrics zero = compare(flat(4, 4, 0.0f), flat(4, 4, 0.0f), linear());
  EXPECT_EQ(zero.sum_ratio[0], 1.0);  // 0 / 0: equal
  EXPECT_TRUE(std::isinf(compare(flat(4, 4, 1.0f), flat(4, 4, 0.0f), linear()).sum_ratio[1]));
}

TEST(Metrics, RandomSignNoiseOfFixedSize) {
  // |a − b| = c at every sample: RMSE = max = c exactly, relative RMSE = c / rms(b).
  const Image b = flat(50, 40, 0.5f);
  std::mt19937 rng(7);
  const float c = 0.02f;
  const Image a = map_image(b, [&](float v, std::size_t) { return rng() & 1u ? v + c : v - c; });
  const Metrics m = compare(a, b);
  EXPECT_NEAR(m.rmse, c, 1e-6);
  EXPECT_NEAR(m.max_abs_error, c, 1e-6);
  EXPECT_NEAR(m.relative_rmse, c / 0.5, 1e-5);
}

TEST(Metrics, GaussianNoiseRmseWithinStatisticalBounds) {
  // n samples of N(0, σ²): the RMSE estimates σ with relative standard error
  // sqrt(1 / 2n); test at 4 standard errors.
  const int w = 64, h = 64;
  const double sigma = 0.01;
  const Image b = flat(w, h, 0.5f);
  std::mt19937 rng(12345);
  std::normal_distribution<double> noise(0.0, sigma);
  const Image a = map_image(b, [&](float v, std::size_t) { return static_cast<float>(v + noise(rng)); });
  const Metrics m = compare(a, b);
  const double n = 3.0 * w * h, se = std::sqrt(1.0 / (2.0 * n));
  EXPECT_NEAR(m.rmse / sigma, 1.0, 4.0 * se);
  EXPECT_NEAR(m.psnr_db, -20.0 * std::log10(sigma), 20.0 * std::log10(1.0 + 4.0 * se) + 1e-9);
  EXPECT_GT(m.max_abs_error, 2.0 * sigma);  // 12288 samples: the max is ~4σ
  EXPECT_LT(m.ssim, 1.0);
}

TEST(Metrics, LinearPeakIsTheReferenceMaximum) {
  Image b = texture(16, 16);
  b.pixel(3, 4)[1] = 4.0f;  // the brightest value of B
  const float c = 0.1f;
  const Image a = map_image(b, [c](float v, std::size_t) { return v + c; });
  const Metrics m = compare(a, b, linear());
  EXPECT_DOUBLE_EQ(m.peak, 4.0);
  EXPECT_NEAR(m.psnr_db, 20.0 * std::log10(4.0 / c), 1e-3);
  // threshold × peak = 0.2 > c: nothing over; 0.02 × 4 = 0.08 < c: everything over.
  EXPECT_EQ(m.fraction_over_threshold, 0.0);
  CompareOptions o = linear();
  o.threshold = 0.02;
  EXPECT_EQ(compare(a, b, o).fraction_over_threshold, 1.0);
  // Display images: the peak stays 1 whatever the values.
  EXPECT_EQ(compare(a, b).peak, 1.0);
}

TEST(Metrics, FractionOverThresholdAndWhereTheMaxIs) {
  const Image b = flat(10, 10, 0.4f);
  Image a = b;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) a.pixel(x, y)[0] += y < 3 ? 0.1f : 0.01f;  // 30% over 0.05
  a.pixel(7, 8)[2] = 0.0f;  // the largest error, 0.4, in blue
  const Metrics m = compare(a, b);
  EXPECT_EQ(m.pixels_over_threshold, 31u);
  EXPECT_DOUBLE_EQ(m.fraction_over_threshold, 0.31);
  EXPECT_NEAR(m.max_abs_error, 0.4, 1e-6);
  EXPECT_EQ(m.max_abs_x, 7);
  EXPECT_EQ(m.max_abs_y, 8);
  const std::vector<float> e = pixel_errors(a, b);
  ASSERT_EQ(e.size(), 100u);
  EXPECT_NEAR(e[8 * 10 + 7], 0.4f, 1e-6f);  // max over channels
  EXPECT_NEAR(e[0], 0.1f, 1e-6f);
}

TEST(Metrics, MaskExcludesBackgroundOfEitherImage) {
  const int w = 20, h = 10;
  const Image ref = texture(w, h);
  Image a = ref, b = ref;
  // A has no geometry in columns 0..4 (and garbage there); B none in rows 0..1.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x < 5) {
        a.pixel(x, y)[3] = 0.0f;
        a.pixel(x, y)[0] = 1000.0f;
      }
      if (y < 2) {
        b.pixel(x, y)[3] = 0.2f;  // below 0.5: background
        b.pixel(x, y)[1] = -50.0f;
      }
    }
  const std::vector<std::uint8_t> mask = geometry_mask(a, b);
  EXPECT_EQ(count_compared(mask), std::size_t(15 * 8));
  EXPECT_EQ(mask[0], 0);
  EXPECT_EQ(mask[static_cast<std::size_t>(5) * w + 5], 1);
  for (const CompareOptions& o : {CompareOptions{}, linear()}) {
    const Metrics m = compare(a, b, o);
    EXPECT_EQ(m.total_pixels, std::size_t(w * h));
    EXPECT_EQ(m.compared_pixels, std::size_t(15 * 8));
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.max_abs_error, 0.0);
    EXPECT_EQ(m.ssim, 1.0);  // the garbage never enters a window
  }
  // A NaN in the background is ignored; in a compared pixel it is an error.
  a.pixel(0, 5)[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NO_THROW(compare(a, b));
  a.pixel(10, 5)[2] = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(first_non_finite(b, mask).has_value());
  ASSERT_TRUE(first_non_finite(a, mask).has_value());
  EXPECT_EQ(*first_non_finite(a, mask), std::make_pair(10, 5));
  EXPECT_THROW(compare(a, b), std::invalid_argument);
}

TEST(Metrics, ImagesWithoutAlphaAreAllGeometry) {
  const Image b = texture(8, 8);  // alpha 1 everywhere, as a PNG without alpha reads
  EXPECT_EQ(compare(b, b).compared_pixels, 64u);
}

TEST(Metrics, BadInputsThrow) {
  const Image a = texture(8, 8);
  EXPECT_THROW(compare(a, texture(8, 9)), std::invalid_argument);
  EXPECT_THROW(geometry_mask(a, texture(9, 8)), std::invalid_argument);
  Image bg = a;
  for (std::size_t i = 3; i < bg.rgba.size(); i += 4) bg.rgba[i] = 0.0f;
  EXPECT_THROW(compare(a, bg), std::invalid_argument);  // no pixel in common
  CompareOptions o;
  o.threshold = -0.1;
  EXPECT_THROW(compare(a, a, o), std::invalid_argument);
}

TEST(Metrics, BlackReference) {
  const Image b = flat(8, 8, 0.0f);
  EXPECT_EQ(compare(b, b, linear()).relative_rmse, 0.0);
  EXPECT_TRUE(std::isinf(compare(b, b, linear()).psnr_db));
  const Image a = flat(8, 8, 0.1f);
  const Metrics m = compare(a, b, linear());
  EXPECT_TRUE(std::isinf(m.relative_rmse));
  EXPECT_TRUE(std::isnan(m.psnr_db));  // no peak to relate the error to
  EXPECT_NEAR(m.rmse, 0.1, 1e-7);
  EXPECT_EQ(m.fraction_over_threshold, 1.0);  // threshold × 0: any error is over
}

TEST(Ssim, FlatImagesFollowTheLuminanceTerm) {
  // σx = σy = σxy = 0: SSIM = (2ab + C1) / (a² + b² + C1) exactly (Wang et al. eq. 13).
  // Grey pixels: the luma is the grey value (the Rec. 709 weights sum to 1).
  const std::vector<std::uint8_t> all(24 * 16, 1);
  for (auto [va, vb] : {std::pair{0.5f, 0.5f}, {0.5f, 0.4f}, {0.2f, 0.8f}, {0.0f, 1.0f}, {0.0f, 0.1f}}) {
    const double a = double(va), b = double(vb);
    const double expected = (2 * a * b + kC1) / (a * a + b * b + kC1);
    EXPECT_NEAR(ssim(flat(24, 16, va), flat(24, 16, vb), all), expected, 1e-6) << va << " " << vb;
  }
}

TEST(Ssim, ContrastReductionIsBelowOneAndSymmetric) {
  const Image a = texture(48, 40);
  const std::vector<std::uint8_t> all(48 * 40, 1);
  double previous = 1.0;
  for (float k : {0.9f, 0.6f, 0.3f}) {
    const Image b = map_image(a, [k](float v, std::size_t) { return 0.45f + k * (v - 0.45f); });
    const double s = ssim(a, b, all);
    EXPECT_LT(s, 1.0) << k;
    EXPECT_GT(s, 0.0) << k;
    EXPECT_LT(s, previous) << k;  // less contrast, less similar
    previous = s;
    EXPECT_EQ(s, ssim(b, a, all)) << k;  // symmetric, bit for bit
  }
}

TEST(Ssim, InvertedStructureIsNegative) {
  const Image a = texture(48, 40);
  const Image b = map_image(a, [](float v, std::size_t) { return 0.9f - v; });
  EXPECT_LT(ssim(a, b, std::vector<std::uint8_t>(48 * 40, 1)), 0.0);
}

TEST(Ssim, MoreNoiseLowersIt) {
  const Image a = texture(48, 40);
  const std::vector<std::uint8_t> all(48 * 40, 1);
  double previous = 1.0;
  for (float sigma : {0.005f, 0.02f, 0.08f}) {
    std::mt19937 rng(3);
    std::normal_distribution<float> noise(0.0f, sigma);
    const Image b = map_image(a, [&](float v, std::size_t) { return v + noise(rng); });
    const double s = ssim(a, b, all);
    EXPECT_LT(s, previous) << sigma;
    previous = s;
  }
}

TEST(Ssim, MapIsZeroOutsideTheMaskAndAveragesToTheResult) {
  const int w = 30, h = 20;
  const Image a = texture(w, h);
  const Image b = map_image(a, [](float v, std::size_t i) { return v + 0.05f * float((i / 4) % 3); });
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(w) * h, 1);
  for (int x = 0; x < w; ++x) mask[x] = mask[static_cast<std::size_t>(19) * w + x] = 0;
  std::vector<float> map;
  const double s = ssim(a, b, mask, &map);
  ASSERT_EQ(map.size(), mask.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (!mask[i]) {
      EXPECT_EQ(map[i], 0.0f);
    }
    sum += map[i];
  }
  EXPECT_NEAR(sum / double(count_compared(mask)), s, 1e-6);
  EXPECT_THROW(ssim(a, b, std::vector<std::uint8_t>(mask.size(), 0)), std::invalid_argument);
}

TEST(Ssim, LinearImagesAreTonemappedFirst) {
  const Image b = map_image(texture(24, 24), [](float v, std::size_t) { return 3.0f * v; });
  const Image a = map_image(b, [](float v, std::size_t) { return 1.1f * v; });
  const std::vector<std::uint8_t> all(24 * 24, 1);
  CompareOptions o = linear();
  o.exposure = 0.5f;
  EXPECT_DOUBLE_EQ(compare(a, b, o).ssim, ssim(tonemap(a, 0.5f), tonemap(b, 0.5f), all));
}

TEST(Ssim, LumaOfGreyIsTheGreyValueAndClamped) {
  const std::vector<float> y = luma(flat(2, 2, 0.3f));
  EXPECT_NEAR(y[0], 0.3f, 1e-6f);
  EXPECT_EQ(luma(flat(1, 1, 7.0f))[0], 1.0f);
  EXPECT_EQ(luma(flat(1, 1, -1.0f))[0], 0.0f);
}

TEST(Ssim, SeparableSumsMatchTheDirectWindowedFormula) {
  // The documented definition evaluated directly: for each compared pixel, the 11×11
  // Gaussian weights over the compared pixels inside the image, renormalized.
  const int w = 26, h = 19;
  const Image a = texture(w, h);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.1f, 0.1f);
  const Image b = map_image(a, [&](float v, std::size_t) { return 0.8f * v + u(rng); });
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(w) * h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if ((x - 4) * (x - 4) + (y - 6) * (y - 6) < 10) mask[static_cast<std::size_t>(y) * w + x] = 0;
  std::vector<float> map;
  ssim(a, b, mask, &map);
  const std::vector<float> X = luma(a), Y = luma(b);
  const int r = kSsimWindow / 2;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (!mask[i]) continue;
      double sw = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          const std::size_t j = static_cast<std::size_t>(yy) * w + xx;
          if (!mask[j]) continue;
          const double k = std::exp(-(dx * dx + dy * dy) / (2 * kSsimSigma * kSsimSigma));
          sw += k;
          sx += k * X[j];
          sy += k * Y[j];
          sxx += k * X[j] * X[j];
          syy += k * Y[j] * Y[j];
          sxy += k * X[j] * Y[j];
        }
      const double mx = sx / sw, my = sy / sw;
      const double vx = sxx / sw - mx * mx, vy = syy / sw - my * my, cxy = sxy / sw - mx * my;
      const double expected = (2 * mx * my + kC1) * (2 * cxy + kC2) /
                              ((mx * mx + my * my + kC1) * (vx + vy + kC2));
      EXPECT_NEAR(map[i], expected, 1e-5) << x << ", " << y;
    }
}
