// sss-compare: error metrics between two renders, optional error maps, and a verdict.
//   sss-compare A B [--heatmap FILE.png] [--log-ratio FILE.png [--log-range STOPS]]
//               [--json] [--tolerance T] [--max-abs E]
//               [--max-fraction F] [--min-ssim S] [--threshold T] [--exposure X]
//               [--variance B.var.exr]
// B is the reference. The metrics are defined in image/Metrics.h. The command-line
// contract is DESIGN.md §4. Exit codes: 0 the images agree within the limits, 3 they do
// not, 2 bad usage or input, 1 a runtime failure (e.g. a map cannot be written).
#include "CliSupport.h"
#include "ExitCodes.h"
#include "Report.h"

#include "image/AtomicFile.h"
#include "image/HeatMap.h"
#include "image/Image.h"
#include "image/Metrics.h"
#include "image/Tonemap.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <optional>
#include <sstream>
#include <variant>

using namespace sss;
using namespace sss::app;

namespace {

int usage(const std::string& message) { return usage_error("sss-compare", message); }

bool is_png_name(const std::string& s) { return lower_extension(s) == ".png"; }

int input_error(const std::string& message) {
  std::cerr << "sss-compare: error: " << message << '\n';
  return kExitUsage;
}

// read_image chooses by magic bytes; so does this (an EXR holds linear values).
image::Encoding encoding_of(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  unsigned char magic[4] = {};
  f.read(reinterpret_cast<char*>(magic), 4);
  static const unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
  return f && std::memcmp(magic, kExr, 4) == 0 ? image::Encoding::Linear : image::Encoding::Display;
}

std::string size_text(const image::Image& img) {
  return std::to_string(img.width) + "x" + std::to_string(img.height);
}

std::size_t geometry_pixels(const image::Image& img) {
  std::size_t n = 0;
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) n += img.rgba[i] > image::kGeometryAlpha;
  return n;
}

struct Args {
  std::string a, b, heatmap, variance, log_ratio;
  double heatmap_max = 0.0;
  double log_range = image::kDefaultLogRange;
  bool json = false, heatmap_signed = false, exclude_silhouettes = false;
  double tolerance = 0.01, threshold = 0.05, max_abs = 0.0, max_fraction = 0.0, min_ssim = 0.0;
  float exposure = 1.0f;
  // Whether these were given (after the parse; their defaults are not limits or files).
  bool has_heatmap = false, has_heatmap_max = false, has_log_ratio = false, has_log_range = false;
  bool has_max_abs = false, has_max_fraction = false, has_min_ssim = false;
};

// The options whose presence matters, to copy into Args once parsed.
struct Given {
  CLI::Option *heatmap, *heatmap_max, *log_ratio, *log_range, *max_abs, *max_fraction, *min_ssim;
  void into(Args& a) const {
    a.has_heatmap = heatmap->count() > 0;
    a.has_heatmap_max = heatmap_max->count() > 0;
    a.has_log_ratio = log_ratio->count() > 0;
    a.has_log_range = log_range->count() > 0;
    a.has_max_abs = max_abs->count() > 0;
    a.has_max_fraction = max_fraction->count() > 0;
    a.has_min_ssim = min_ssim->count() > 0;
  }
};

Given add_options(CLI::App& app, Args& a) {
  app.footer(
      "Exit status: 0 the images agree (relative RMSE <= --tolerance and every other limit "
      "given holds), 3 they do not, 2 bad usage or input, 1 runtime failure.\n"
      "A PNG compared with an EXR: the EXR is tonemapped (--exposure) and both are compared "
      "as display values.");
  Given g{};
  app.add_option("A", a.a, "The image under test (PNG or EXR)")->required();
  app.add_option("B", a.b, "The reference image (PNG or EXR), same size as A")->required();
  g.heatmap = app.add_option("--heatmap", a.heatmap,
                             "Write a heat map of the per-pixel error max_c |a-b| (FILE.png)");
  g.heatmap_max =
      app.add_option("--heatmap-max", a.heatmap_max,
                     "Top of the heat map's scale (default: the 99th percentile of the compared "
                     "pixels' errors; the few above it take the top colour)")
          ->needs(g.heatmap);
  app.add_flag("--heatmap-signed", a.heatmap_signed,
               "The heat map shows the signed error a-b of each pixel's worst channel: red where "
               "A is above the reference, blue below, white equal; its scale runs from -top to "
               "+top")
      ->needs(g.heatmap);
  app.add_flag("--exclude-silhouettes", a.exclude_silhouettes,
               "Leave out every pixel next to one without geometry in A or B (the silhouettes, "
               "where a raster and a ray tracer pick different triangles), as the golden suite's "
               "tests/golden/REPORT.md does");
  g.log_ratio = app.add_option(
      "--log-ratio", a.log_ratio,
      "Write a map of the signed log ratio log2(A/B) of each pixel's luminance (FILE.png): "
      "blue A darker, white equal, red A brighter");
  g.log_range =
      app.add_option("--log-range", a.log_range,
                     "Stops at which the --log-ratio map saturates (default 1: 2x brighter or darker)")
          ->needs(g.log_ratio);
  app.add_flag("--json", a.json, "Print one JSON document on stdout and nothing else");
  app.add_option("--tolerance", a.tolerance, "Largest relative RMSE that passes (default 0.01)");
  g.max_abs = app.add_option("--max-abs", a.max_abs, "Also require max abs error <= E");
  g.max_fraction = app.add_option("--max-fraction", a.max_fraction,
                                  "Also require the fraction over --threshold <= F");
  g.min_ssim = app.add_option("--min-ssim", a.min_ssim, "Also require SSIM >= S");
  app.add_option("--variance", a.variance,
                 "B's variance of the mean (an EXR, e.g. sss-reference --method random-walk --variance): report "
                 "B's noise and judge --tolerance on the relative RMSE with that noise subtracted");
  app.add_option("--threshold", a.threshold,
                 "Per-pixel error threshold, a fraction of the peak (default 0.05)");
  app.add_option("--exposure", a.exposure, "Exposure when tonemapping an EXR (default 1)");
  return g;
}

// Every value in its range and every file name of the right kind; an exit status where not.
std::optional<int> check_values(const Args& a) {
  auto non_negative = [](const char* name, double v) -> std::optional<int> {
    if (std::isfinite(v) && v >= 0.0) return std::nullopt;
    std::ostringstream s;
    s << name << ": expected a finite number >= 0, got " << v;
    return usage(s.str());
  };
  const std::initializer_list<std::pair<const char*, double>> non_negatives = {
      {"--tolerance", a.tolerance},
      {"--threshold", a.threshold},
      {"--max-abs", a.max_abs},
      {"--max-fraction", a.max_fraction}};
  for (const auto& [name, v] : non_negatives)
    if (auto code = non_negative(name, v)) return code;
  if (a.max_fraction > 1.0)
    return usage("--max-fraction: expected a fraction in [0, 1], got " + std::to_string(a.max_fraction));
  if (!(a.min_ssim >= -1.0 && a.min_ssim <= 1.0))
    return usage("--min-ssim: expected a number in [-1, 1], got " + std::to_string(a.min_ssim));
  if (!(std::isfinite(a.exposure) && a.exposure > 0.0f))
    return usage("--exposure: expected a finite number > 0, got " + std::to_string(a.exposure));
  if (a.has_heatmap_max && !(std::isfinite(a.heatmap_max) && a.heatmap_max > 0.0))
    return usage("--heatmap-max: expected a finite number > 0, got " + std::to_string(a.heatmap_max));
  if (a.has_heatmap && !is_png_name(a.heatmap))
    return usage("--heatmap: expected a .png file name, got '" + a.heatmap + "'");
  if (a.has_log_range && !(std::isfinite(a.log_range) && a.log_range > 0.0))
    return usage("--log-range: expected a finite number of stops > 0, got " + std::to_string(a.log_range));
  if (a.has_log_ratio && !is_png_name(a.log_ratio))
    return usage("--log-ratio: expected a .png file name, got '" + a.log_ratio + "'");
  return std::nullopt;
}

// A and B read, checked and brought to one encoding, with the pixels to compare.
struct Inputs {
  image::Image img[2];
  InputInfo info[2];
  std::size_t silhouette = 0;  // pixels --exclude-silhouettes left out
  std::vector<std::uint8_t> mask;
  image::Encoding space = image::Encoding::Linear;
  image::Image variance;  // --variance, or empty
};

// The inputs, or an exit status (with its message printed).
std::variant<Inputs, int> read_inputs(const Args& a) {
  Inputs in;
  image::Image (&img)[2] = in.img;
  InputInfo (&info)[2] = in.info;
  for (int i = 0; i < 2; ++i) {
    const std::string& path = i == 0 ? a.a : a.b;
    auto read = image::read_image(path);
    if (auto* e = std::get_if<image::ImageError>(&read)) return input_error(e->what());
    img[i] = std::move(std::get<image::Image>(read));
    info[i] = {path, img[i].width, img[i].height, encoding_of(path), false};
  }
  if (img[0].width != img[1].width || img[0].height != img[1].height)
    return input_error("images differ in size: " + a.a + " is " + size_text(img[0]) + ", " + a.b +
                       " is " + size_text(img[1]));
  const std::size_t silhouette = a.exclude_silhouettes ? image::exclude_silhouettes(img[0], img[1]) : 0;
  in.silhouette = silhouette;
  in.mask = image::geometry_mask(img[0], img[1]);
  const std::size_t compared = image::count_compared(in.mask);
  if (compared == 0)
    return input_error("no pixel to compare: " + a.a + " has geometry (alpha > 0.5) in " +
                       std::to_string(geometry_pixels(img[0])) + " pixels, " + a.b + " in " +
                       std::to_string(geometry_pixels(img[1])) + ", and no pixel has it in both" +
                       (silhouette > 0 ? " away from a silhouette (--exclude-silhouettes left out " +
                                             std::to_string(silhouette) + ")"
                                       : std::string()));
  for (int i = 0; i < 2; ++i)
    if (auto bad = image::first_non_finite(img[i], in.mask))
      return input_error(info[i].path + ": pixel (" + std::to_string(bad->first) + ", " +
                         std::to_string(bad->second) + ") has a non-finite R, G or B value");
  if (info[0].encoding != info[1].encoding) {
    in.space = image::Encoding::Display;
    for (int i = 0; i < 2; ++i)
      if (info[i].encoding == image::Encoding::Linear) {
        img[i] = image::tonemap(img[i], a.exposure);
        info[i].tonemapped = true;
      }
  } else {
    in.space = info[0].encoding;
  }

  if (!a.variance.empty()) {
    if (in.space != image::Encoding::Linear || info[1].encoding != image::Encoding::Linear)
      return usage("--variance: needs A and B as EXR (linear) images");
    auto read = image::read_image(a.variance);
    if (auto* e = std::get_if<image::ImageError>(&read)) return input_error(e->what());
    in.variance = std::move(std::get<image::Image>(read));
    if (encoding_of(a.variance) != image::Encoding::Linear)
      return input_error(a.variance + ": --variance must be an EXR");
    if (in.variance.width != img[1].width || in.variance.height != img[1].height)
      return input_error(a.variance + " is " + size_text(in.variance) + ", " + a.b + " is " + size_text(img[1]));
  }
  return in;
}

// --heatmap: the per-pixel error map, its scale into the report.
void write_heatmap(const Args& a, const Inputs& in, Report& report) {
  const image::Image (&img)[2] = in.img;
  const std::vector<float> errors = a.heatmap_signed ? image::signed_pixel_errors(img[0], img[1])
                                                     : image::pixel_errors(img[0], img[1]);
  double top = a.heatmap_max;
  report.heatmap_scale = "given";
  if (!a.has_heatmap_max) {
    top = image::robust_scale(errors, in.mask);
    report.heatmap_scale = "p99";
    if (!(top > 0.0)) {  // 99% of the pixels equal: the largest error, or 1 if none
      top = report.metrics.max_abs_error > 0.0 ? report.metrics.max_abs_error : 1.0;
      report.heatmap_scale = report.metrics.max_abs_error > 0.0 ? "max" : "none";
    }
  }
  for (std::size_t i = 0; i < errors.size(); ++i)
    report.heatmap_above += in.mask[i] && std::fabs(errors[i]) > top;
  const image::Image map =
      a.heatmap_signed ? image::render_signed_heatmap(errors, in.mask, img[0].width, img[0].height, top)
                       : image::render_heatmap(errors, in.mask, img[0].width, img[0].height, top);
  image::write_png(a.heatmap, map);
  report.heatmap = a.heatmap;
  report.heatmap_max = top;
  report.heatmap_signed = a.heatmap_signed;
}

// --log-ratio: log2(A/B) of the luminance, in the space the metrics were taken in (display
// values are linearized inside).
void write_log_ratio(const Args& a, const Inputs& in, Report& report) {
  const std::vector<float> r = image::log2_luminance_ratio(in.img[0], in.img[1], in.space);
  const image::Image map =
      image::render_log_ratio_map(r, in.mask, in.img[0].width, in.img[0].height, a.log_range);
  image::write_png(a.log_ratio, map);
  report.log_ratio = a.log_ratio;
  report.log_range = a.log_range;
  report.log_stats = image::log_ratio_stats(r, in.mask);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "sss-compare: error metrics between a test image A and a reference image B (PNG or EXR), "
      "over the pixels where both have geometry (alpha > 0.5).\n"
      "Metrics: relative RMSE sqrt(sum (a-b)^2 / sum b^2) over R, G, B; RMSE; PSNR (peak 1 "
      "for PNG, the largest value of B for EXR); max abs error; the fraction of pixels whose "
      "error max_c |a-b| exceeds --threshold x peak; SSIM of the luma (EXR tonemapped first).",
      "sss-compare"};
  Args a;
  const Given given = add_options(app, a);
  if (const auto stop = parse_command_line(app, argc, argv, "sss-compare")) return *stop;
  given.into(a);
  if (const auto code = check_values(a)) return *code;
  auto inputs = read_inputs(a);
  if (const int* code = std::get_if<int>(&inputs)) return *code;
  const Inputs& in = std::get<Inputs>(inputs);

  Report report;
  report.a = in.info[0];
  report.b = in.info[1];
  report.space = in.space;
  report.exposure = a.exposure;
  report.silhouette_pixels = a.exclude_silhouettes ? std::optional<std::size_t>(in.silhouette) : std::nullopt;
  report.limits.tolerance = a.tolerance;
  if (a.has_max_abs) report.limits.max_abs = a.max_abs;
  if (a.has_max_fraction) report.limits.max_fraction = a.max_fraction;
  if (a.has_min_ssim) report.limits.min_ssim = a.min_ssim;

  try {
    image::CompareOptions options;
    options.encoding = in.space;
    options.threshold = a.threshold;
    options.exposure = a.exposure;
    if (!a.variance.empty()) options.reference_variance = &in.variance;
    report.metrics = image::compare(in.img[0], in.img[1], options);
    report.checks = evaluate(report.metrics, report.limits);
    if (a.has_heatmap) write_heatmap(a, in, report);
    if (a.has_log_ratio) write_log_ratio(a, in, report);
  } catch (const std::invalid_argument& e) {
    return input_error(e.what());
  } catch (const std::exception& e) {
    std::cerr << "sss-compare: error: " << e.what() << '\n';
    return kExitRuntime;
  }

  if (a.json)
    std::cout << to_json(report).dump(2) << '\n';
  else
    std::cout << to_table(report);
  std::cout.flush();
  if (!std::cout) {
    std::cerr << "sss-compare: error: cannot write to stdout\n";
    return kExitRuntime;
  }
  return all_pass(report.checks) ? kExitOk : kExitDiffer;
}
