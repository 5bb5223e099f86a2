// Error metrics between a test image A and a reference image B (sss-compare, golden-image
// tests). Every metric is taken over the *compared pixels* only: those where both images
// have geometry, i.e. alpha > 0.5 in A and in B (the renderers write alpha 1 on geometry
// and 0 on the background, in EXR and PNG alike; an image without an alpha channel reads
// as alpha 1 everywhere, so all of it is geometry). Let M be that set, N = |M|, and a, b
// the R, G, B values of A and B (alpha is never compared). Sums run over i in M and the
// three channels c:
//
//   RMSE            sqrt( Σ (a − b)² / 3N )
//   relative RMSE   sqrt( Σ (a − b)² / Σ b² )  — B is the reference; the ratio of the error's
//                   energy to the reference's. A = k·B gives |k − 1|. 0 when both sums are
//                   0, +∞ when only Σ b² is (a black reference against a non-black image).
//   peak            1 for display-encoded images (PNG: sRGB codes / 255); for linear (HDR)
//                   images the largest R, G or B value of B over M.
//   PSNR            10·log10(peak² / RMSE²) in dB; +∞ when RMSE = 0, NaN when the pixels
//                   differ but the peak is not positive (a black linear reference).
//   pixel error     e = max_c |a_c − b_c|, per pixel, in the images' own units.
//   max abs error   the largest e over M (and where it is).
//   over threshold  the fraction of M with e > threshold · peak (threshold 0.05 by default:
//                   5% of the peak, which is 12.75 codes of an 8-bit PNG).
//   SSIM            the mean structural similarity (below) of the luma of the display
//                   images, over M.
//
// When B is a Monte Carlo estimate with a known variance of its mean v per pixel and
// channel (sss-reference --method random-walk --variance), its own noise inflates the
// squared error in expectation: E[Σ (a − b̂)²] = Σ (a − b)² + Σ v, and E[Σ b̂²] = Σ b² + Σ v.
// So (CompareOptions::reference_variance):
//   reference noise        sqrt( Σ v / (Σ b² − Σ v) ), B's relative RMS noise
//   noise-subtracted relative RMSE
//                          sqrt( max(0, Σ (a − b)² − Σ v) / (Σ b² − Σ v) ), an unbiased
//                          estimate of the squared error against B's expectation (the
//                          relative RMSE A would have against a noiseless B)
//
// Why SSIM as the perceptual metric (and not ꟻLIP, Andersson et al. 2020, "ꟻLIP: A
// Difference Evaluator for Alternating Images", Proc. ACM CGIT 3(2)): SSIM is the standard
// one, its behaviour is well understood (1 for identical images, symmetric, closed forms
// for flat images), it is cheap (a separable blur of six images) and has no viewing-
// condition parameters to argue about. Its limits, which the other metrics cover: it sees
// luma only, so a pure hue error (a wrong scattering colour at equal luma) is invisible to
// it; it is single-scale, so its verdict depends on the viewing distance (MS-SSIM, Wang,
// Simoncelli and Bovik 2003, addresses that); the mean hides a small, strongly wrong
// region; and HDR images are judged only after tonemapping, i.e. at one exposure.
//
// SSIM as in Wang, Bovik, Sheikh and Simoncelli 2004, "Image Quality Assessment: From Error
// Visibility to Structural Similarity", IEEE TIP 13(4), eq. 13 and §III-C:
//   SSIM(x, y) = (2 μx μy + C1)(2 σxy + C2) / ((μx² + μy² + C1)(σx² + σy² + C2))
// with μ, σ², σxy taken under a normalized 11×11 Gaussian window of σ = 1.5, C1 = (K1 L)²,
// C2 = (K2 L)², K1 = 0.01, K2 = 0.03, L = 1 (values in [0, 1]). The signal is Rec. 709
// luma Y' = 0.2126 R' + 0.7152 G' + 0.0722 B' of the display-encoded values (the paper
// works on 8-bit grey levels, i.e. on gamma-encoded values too); linear images are first
// tonemapped with image::tonemap (the display transform of the real-time composite).
// Background pixels and the outside of the image get weight 0 in every window, and the
// window's remaining weights are renormalized (normalized convolution, Knutsson and Westin
// 1993, "Normalized and Differential Convolution", CVPR): the statistics near a silhouette
// or an edge of the image come from the compared pixels only, and no border is cropped.
#pragma once

#include "image/Image.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace sss::image {

// How an image's values are encoded: display values in [0, 1] (a PNG: sRGB codes / 255)
// or linear radiance (an EXR).
enum class Encoding { Display, Linear };
const char* encoding_name(Encoding e);  // "display" or "linear"

inline constexpr float kGeometryAlpha = 0.5f;  // alpha above this is geometry

// SSIM constants (Wang et al. 2004).
inline constexpr int kSsimWindow = 11;
inline constexpr double kSsimSigma = 1.5, kSsimK1 = 0.01, kSsimK2 = 0.03;

struct CompareOptions {
  Encoding encoding = Encoding::Display;  // of both images; convert a mixed pair first
  double threshold = 0.05;                // of the peak, for the "over threshold" fraction
  float exposure = 1.0f;                  // tonemap exposure before SSIM (linear images)
  // B's variance of the mean per pixel and channel (linear images only, B's size): the
  // metrics then state B's noise and subtract it (above). Not owned.
  const Image* reference_variance = nullptr;
};

struct Metrics {
  std::size_t total_pixels = 0;
  std::size_t compared_pixels = 0;  // N
  double rmse = 0.0;
  double relative_rmse = 0.0;
  double peak = 1.0;
  double psnr_db = 0.0;
  double max_abs_error = 0.0;
  int max_abs_x = -1, max_abs_y = -1;  // a pixel with the largest error (-1: none)
  double threshold = 0.05;             // as given (a fraction of the peak)
  std::size_t pixels_over_threshold = 0;
  double fraction_over_threshold = 0.0;
  double ssim = 1.0;
  // Σ a_c / Σ b_c over the compared pixels, per channel: the summed radiance's ratio, the
  // bias that a relative RMSE does not show (inf where B sums to 0 and A does not).
  std::array<double, 3> sum_ratio{1.0, 1.0, 1.0};
  bool has_reference_noise = false;  // a reference variance was given
  double reference_noise = 0.0;
  double relative_rmse_noise_subtracted = 0.0;
};

// 1 where both images have geometry (alpha > kGeometryAlpha), else 0; row-major. Throws
// std::invalid_argument if the sizes differ.
std::vector<std::uint8_t> geometry_mask(const Image& a, const Image& b);
std::size_t count_compared(const std::vector<std::uint8_t>& mask);

// Leaves the silhouettes out of a comparison: every pixel within one pixel (its 3×3
// neighbourhood) of a pixel without geometry in A or in B gets alpha 0 in both images, so
// geometry_mask() and everything built on it (compare(), the maps) skip it. The frame's
// border is not a silhouette. Why: at a silhouette the rasterizer and a ray tracer may
// pick different triangles for the pixel centre, and a grazing specular highlight on one
// of them is a single-pixel spike (up to 4.6 in radiance on builtin:bunny's ear) that says
// nothing about scattering; the golden suite (tests/golden/REPORT.md) compares this way,
// and so does `sss-compare --exclude-silhouettes`. Returns how many pixels with geometry
// in both were left out. Throws std::invalid_argument if the sizes differ.
std::size_t exclude_silhouettes(Image& a, Image& b);

// The first pixel (x, y) in the mask with a non-finite R, G or B value, if any.
std::optional<std::pair<int, int>> first_non_finite(const Image& img,
                                                    const std::vector<std::uint8_t>& mask);

// e = max_c |a_c − b_c| for every pixel (the heat map's values; masked pixels included).
std::vector<float> pixel_errors(const Image& a, const Image& b);

// Rec. 709 luma of display values, clamped to [0, 1].
std::vector<float> luma(const Image& display);

// Mean SSIM of two display-encoded images over the mask (see above). The SSIM map (0
// outside the mask) is written to *map when it is given. Throws std::invalid_argument if
// the sizes differ or the mask is empty.
double ssim(const Image& a_display, const Image& b_display, const std::vector<std::uint8_t>& mask,
            std::vector<float>* map = nullptr);

// All of the above. Throws std::invalid_argument when the sizes differ, no pixel has
// geometry in both, a compared value is not finite, or the threshold is negative.
Metrics compare(const Image& a, const Image& b, const CompareOptions& options = {});

}  // namespace sss::image
