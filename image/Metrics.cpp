#include "image/Metrics.h"

#include "image/Tonemap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sss::image {

namespace {

void require_same_size(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("images differ in size: " + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + " and " + std::to_string(b.width) +
                                "x" + std::to_string(b.height));
  if (a.rgba.size() != static_cast<std::size_t>(a.width) * a.height * 4 ||
      b.rgba.size() != a.rgba.size())
    throw std::invalid_argument("image buffer does not match its size");
}

void require_mask(const Image& a, const std::vector<std::uint8_t>& mask) {
  if (mask.size() != static_cast<std::size_t>(a.width) * a.height)
    throw std::invalid_argument("mask does not match the image size");
}

// The normalized 1D Gaussian of the SSIM window (the 2D window is its outer product).
std::array<double, kSsimWindow> ssim_kernel() {
  std::array<double, kSsimWindow> k{};
  const int r = kSsimWindow / 2;
  double sum = 0.0;
  for (int i = 0; i < kSsimWindow; ++i) {
    const double x = i - r;
    k[i] = std::exp(-x * x / (2.0 * kSsimSigma * kSsimSigma));
    sum += k[i];
  }
  for (double& v : k) v /= sum;
  return k;
}

}  // namespace

const char* encoding_name(Encoding e) { return e == Encoding::Linear ? "linear" : "display"; }

std::vector<std::uint8_t> geometry_mask(const Image& a, const Image& b) {
  require_same_size(a, b);
  const std::size_t n = static_cast<std::size_t>(a.width) * a.height;
  std::vector<std::uint8_t> mask(n);
  for (std::size_t i = 0; i < n; ++i)
    mask[i] = a.rgba[i * 4 + 3] > kGeometryAlpha && b.rgba[i * 4 + 3] > kGeometryAlpha;
  return mask;
}

std::size_t count_compared(const std::vector<std::uint8_t>& mask) {
  return static_cast<std::size_t>(std::count(mask.begin(), mask.end(), std::uint8_t{1}));
}

std::size_t exclude_silhouettes(Image& a, Image& b) {
  const std::vector<std::uint8_t> geometry = geometry_mask(a, b);
  const int w = a.width, h = a.height;
  std::size_t excluded = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!geometry[std::size_t(y) * w + x]) continue;
      bool edge = false;
      for (int dy = -1; dy <= 1 && !edge; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;  // the border is not a silhouette
          if (!geometry[std::size_t(yy) * w + xx]) edge = true;
        }
      if (!edge) continue;
      a.pixel(x, y)[3] = b.pixel(x, y)[3] = 0.0f;
      ++excluded;
    }
  return excluded;
}

std::optional<std::pair<int, int>> first_non_finite(const Image& img,
                                                    const std::vector<std::uint8_t>& mask) {
  require_mask(img, mask);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (!mask[static_cast<std::size_t>(y) * img.width + x]) continue;
      const float* p = img.pixel(x, y);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        return std::pair{x, y};
    }
  return std::nullopt;
}

std::vector<float> pixel_errors(const Image& a, const Image& b) {
  require_same_size(a, b);
  const std::size_t n = static_cast<std::size_t>(a.width) * a.height;
  std::vector<float> e(n);
  for (std::size_t i = 0; i < n; ++i) {
    float m = 0.0f;
    for (int c = 0; c < 3; ++c) m = std::max(m, std::fabs(a.rgba[i * 4 + c] - b.rgba[i * 4 + c]));
    e[i] = m;
  }
  return e;
}

std::vector<float> luma(const Image& display) {
  const std::size_t n = static_cast<std::size_t>(display.width) * display.height;
  std::vector<float> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &display.rgba[i * 4];
    const float v = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    y[i] = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
  }
  return y;
}

namespace {

// The window sums of m, m·x, m·y, m·x², m·y², m·x·y, where m is the mask: a horizontal
// pass per row into a ring of kSsimWindow rows, which the vertical pass per output pixel
// reads. Products are formed as x·y before the weight so that swapping A and B, or passing
// the same image twice, gives bit-identical sums (SSIM exactly symmetric, exactly 1).
struct SsimRows {
  static constexpr int kQ = 6;
  const std::vector<float>& X;
  const std::vector<float>& Y;
  const std::vector<std::uint8_t>& mask;
  const std::array<double, kSsimWindow>& k;
  int w, r;
  std::vector<double> ring = std::vector<double>(static_cast<std::size_t>(kSsimWindow) * kQ * w);

  double* row(int y) { return &ring[static_cast<std::size_t>(y % kSsimWindow) * kQ * w]; }
  void horizontal(int y) {
    double* out = row(y);
    const std::size_t base = static_cast<std::size_t>(y) * w;
    for (int x = 0; x < w; ++x) {
      double s[kQ] = {};
      for (int j = std::max(0, x - r); j <= std::min(w - 1, x + r); ++j) {
        if (!mask[base + j]) continue;
        const double kw = k[j - x + r], xv = X[base + j], yv = Y[base + j];
        s[0] += kw;
        s[1] += kw * xv;
        s[2] += kw * yv;
        s[3] += kw * (xv * xv);
        s[4] += kw * (yv * yv);
        s[5] += kw * (xv * yv);
      }
      for (int q = 0; q < kQ; ++q) out[static_cast<std::size_t>(q) * w + x] = s[q];
    }
  }
};

// One window's SSIM from its sums (s[0] > 0).
double window_ssim(const double (&s)[SsimRows::kQ]) {
  const double c1 = (kSsimK1 * 1.0) * (kSsimK1 * 1.0), c2 = (kSsimK2 * 1.0) * (kSsimK2 * 1.0);
  const double mx = s[1] / s[0], my = s[2] / s[0];
  const double vx = s[3] / s[0] - mx * mx, vy = s[4] / s[0] - my * my;
  const double cxy = s[5] / s[0] - mx * my;
  return ((2.0 * mx * my + c1) * (2.0 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
}

}  // namespace

double ssim(const Image& a_display, const Image& b_display, const std::vector<std::uint8_t>& mask,
            std::vector<float>* map) {
  require_same_size(a_display, b_display);
  require_mask(a_display, mask);
  const std::size_t compared = count_compared(mask);
  if (compared == 0) throw std::invalid_argument("SSIM: no pixel to compare");
  const int w = a_display.width, h = a_display.height, r = kSsimWindow / 2;
  const std::vector<float> X = luma(a_display), Y = luma(b_display);
  const std::array<double, kSsimWindow> k = ssim_kernel();
  if (map) map->assign(mask.size(), 0.0f);
  constexpr int kQ = SsimRows::kQ;
  SsimRows rows{X, Y, mask, k, w, r};
  double total = 0.0;
  for (int row = 0; row < std::min(h, r); ++row) rows.horizontal(row);
  for (int y = 0; y < h; ++y) {
    if (y + r < h) rows.horizontal(y + r);
    const int y0 = std::max(0, y - r), y1 = std::min(h - 1, y + r);
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (!mask[i]) continue;
      double s[kQ] = {};
      for (int yy = y0; yy <= y1; ++yy) {
        const double kw = k[yy - y + r];
        const double* in = rows.row(yy);
        for (int q = 0; q < kQ; ++q) s[q] += kw * in[static_cast<std::size_t>(q) * w + x];
      }
      // s[0] > 0: the window's centre is a compared pixel with the largest weight.
      const double v = window_ssim(s);
      total += v;
      if (map) (*map)[i] = static_cast<float>(v);
    }
  }
  return total / static_cast<double>(compared);
}

namespace {

// Σ (a − b)² and Σ b² over the compared pixels' channels.
struct ErrorSums {
  double se = 0.0, sb = 0.0;
};

// The per-pixel pass: the sums, the largest absolute error and where, the pixels whose
// largest channel error is over `limit`, and the per-channel sum ratios a / b.
ErrorSums sum_errors(const Image& a, const Image& b, const std::vector<std::uint8_t>& mask, double limit, Metrics& m) {
  const int w = a.width;
  double se = 0.0, sb = 0.0;
  std::array<double, 3> sum_a{}, sum_b{};
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    double e = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double av = a.rgba[i * 4 + c], bv = b.rgba[i * 4 + c], d = av - bv;
      sum_a[std::size_t(c)] += av;
      sum_b[std::size_t(c)] += bv;
      se += d * d;
      sb += bv * bv;
      e = std::max(e, std::fabs(d));
    }
    if (m.max_abs_x < 0 || e > m.max_abs_error) {
      m.max_abs_error = e;
      m.max_abs_x = static_cast<int>(i % w);
      m.max_abs_y = static_cast<int>(i / w);
    }
    if (e > limit) ++m.pixels_over_threshold;
  }
  for (std::size_t c = 0; c < 3; ++c)
    m.sum_ratio[c] = sum_b[c] != 0.0 ? sum_a[c] / sum_b[c]
                     : sum_a[c] == 0.0 ? 1.0
                                       : std::numeric_limits<double>::infinity();
  return {se, sb};
}

// The reference's own noise from its variance image v (linear images only): its relative
// size and the relative RMSE with it subtracted.
void subtract_reference_noise(const Image& b, const Image& v, const std::vector<std::uint8_t>& mask,
                              const CompareOptions& options, const ErrorSums& sums, Metrics& m) {
  const int w = b.width;
  const double se = sums.se, sb = sums.sb;
  if (options.encoding != Encoding::Linear)
    throw std::invalid_argument("a reference variance applies to linear (EXR) images only");
  require_same_size(b, v);
  double sv = 0.0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i])
      for (int c = 0; c < 3; ++c) {
        const double var = v.rgba[i * 4 + c];
        if (!(std::isfinite(var) && var >= 0.0))
          throw std::invalid_argument("reference variance at pixel (" + std::to_string(i % w) + ", " +
                                      std::to_string(i / w) + ") is not a finite number >= 0");
        sv += var;
      }
  m.has_reference_noise = true;
  const double signal = sb - sv;
  m.reference_noise = signal > 0.0 ? std::sqrt(sv / signal) : std::numeric_limits<double>::infinity();
  m.relative_rmse_noise_subtracted =
      signal > 0.0 ? std::sqrt(std::max(0.0, se - sv) / signal) : std::numeric_limits<double>::infinity();
}

}  // namespace

Metrics compare(const Image& a, const Image& b, const CompareOptions& options) {
  require_same_size(a, b);
  if (!(options.threshold >= 0.0) || !std::isfinite(options.threshold))
    throw std::invalid_argument("threshold must be a finite number >= 0");
  const std::vector<std::uint8_t> mask = geometry_mask(a, b);
  Metrics m;
  m.total_pixels = mask.size();
  m.compared_pixels = count_compared(mask);
  m.threshold = options.threshold;
  if (m.compared_pixels == 0)
    throw std::invalid_argument("no pixel has geometry (alpha > 0.5) in both images");
  for (const Image* img : {&a, &b})
    if (auto bad = first_non_finite(*img, mask))
      throw std::invalid_argument("non-finite value at pixel (" + std::to_string(bad->first) +
                                  ", " + std::to_string(bad->second) + ")");

  m.peak = 1.0;
  if (options.encoding == Encoding::Linear) {
    m.peak = 0.0;
    for (std::size_t i = 0; i < mask.size(); ++i)
      if (mask[i])
        for (int c = 0; c < 3; ++c) m.peak = std::max(m.peak, double(b.rgba[i * 4 + c]));
  }
  const double limit = options.threshold * std::max(m.peak, 0.0);

  const ErrorSums sums = sum_errors(a, b, mask, limit, m);
  const double se = sums.se, sb = sums.sb;
  if (const Image* v = options.reference_variance) subtract_reference_noise(b, *v, mask, options, sums, m);
  const double n3 = 3.0 * static_cast<double>(m.compared_pixels);
  const double mse = se / n3;
  m.rmse = std::sqrt(mse);
  if (sb > 0.0)
    m.relative_rmse = std::sqrt(se / sb);
  else
    m.relative_rmse = se == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  if (mse == 0.0)
    m.psnr_db = std::numeric_limits<double>::infinity();
  else if (m.peak > 0.0)
    m.psnr_db = 10.0 * std::log10(m.peak * m.peak / mse);
  else
    m.psnr_db = std::numeric_limits<double>::quiet_NaN();
  m.fraction_over_threshold =
      static_cast<double>(m.pixels_over_threshold) / static_cast<double>(m.compared_pixels);

  if (options.encoding == Encoding::Linear)
    m.ssim = ssim(tonemap(a, options.exposure), tonemap(b, options.exposure), mask);
  else
    m.ssim = ssim(a, b, mask);
  return m;
}

}  // namespace sss::image
