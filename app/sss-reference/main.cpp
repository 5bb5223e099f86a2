// sss-reference: the offline CPU renderers (DESIGN.md §4, §6).
//   sss-reference SCENE --out FILE.exr [--method diffusion|random-walk] ...
//   sss-reference merge TILE.exr... --out FILE.exr [--variance FILE.exr]
// --method diffusion (default): the Jensen–Buhler reference with the exact diffusion
// profile. --method random-walk: the ground truth, volumetric transport through the
// scene's meshes (renderer/reference/GroundTruth.h), with its variance, a sample count or
// a target error, and tiles that `merge` puts together.
// Errors exit 2 (usage, input) or 1 (runtime); Ctrl-C (SIGTERM) stops the render, writes
// nothing and exits 130 (143).
#include "CliSupport.h"
#include "EnvironmentArgs.h"
#include "MaterialOverrides.h"

#include "renderer/image/AtomicFile.h"
#include "renderer/image/Image.h"
#include "renderer/image/Tonemap.h"
#include "renderer/reference/GroundTruth.h"
#include "renderer/reference/ReferenceRenderer.h"
#include "renderer/reference/TileMerge.h"
#include "renderer/scene/BuiltinScenes.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>

using namespace sss;
using namespace sss::app;

namespace {

std::atomic<bool> g_cancel{false};
std::atomic<int> g_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

// SIGINT (Ctrl-C) and SIGTERM (kill, a CI timeout) stop the render the same way: nothing
// is written, an existing output stays as it was, and the exit status is 128 + the signal.
extern "C" void on_interrupt(int sig) {
  g_signal.store(sig);
  g_cancel.store(true);
  std::signal(sig, SIG_DFL);  // a second signal ends the process at once
}

int usage(const std::string& message) { return usage_error("sss-reference", message); }

std::string duration(double seconds) {
  char buf[32];
  const long s = long(std::lround(std::max(seconds, 0.0)));
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  else if (s >= 60) std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%lds", s);
  return buf;
}

// A one-line bar redrawn in place on a terminal, with the time left once a stage has run a
// second; on a pipe or file, a line per stage done and, for long stages, one every 10%.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), tty_(isatty(STDERR_FILENO) == 1) {}
  void operator()(const char* stage, double fraction) {
    if (!enabled_) return;
    const std::string name(stage);
    const auto now = std::chrono::steady_clock::now();
    fraction = std::clamp(fraction, 0.0, 1.0);
    // A stage that starts over (the random walk's next pass towards a target error) is
    // timed and reported afresh.
    if (name != stage_ || fraction + 0.01 < fraction_) {
      stage_start_ = now;
      last_tenth_ = 0;
      if (name == stage_done_) stage_done_.clear();
    }
    fraction_ = fraction;
    const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
    const int percent = int(fraction * 100.0);
    std::string eta;
    if (elapsed > 1.0 && fraction > 0.0 && fraction < 1.0) eta = "  ETA " + duration(elapsed * (1.0 - fraction) / fraction);
    if (tty_) {
      if (name == stage_ && percent == percent_ && eta == eta_) return;
      const int width = 30, filled = percent * width / 100;
      std::fprintf(stderr, "\r%-10s [%s%s] %3d%%%-14s", stage, std::string(std::size_t(filled), '#').c_str(),
                   std::string(std::size_t(width - filled), '.').c_str(), percent, eta.c_str());
      if (percent == 100) std::fputc('\n', stderr);
      std::fflush(stderr);
    } else if (percent == 100 && name != stage_done_) {
      std::fprintf(stderr, "sss-reference: %s done (%s)\n", stage, duration(elapsed).c_str());
      stage_done_ = name;
    } else if (elapsed > 10.0 && percent / 10 > last_tenth_) {
      last_tenth_ = percent / 10;
      std::fprintf(stderr, "sss-reference: %s %d%%%s\n", stage, percent, eta.c_str());
    }
    stage_ = name;
    percent_ = percent;
    eta_ = eta;
  }

 private:
  bool enabled_, tty_;
  std::string stage_, stage_done_, eta_;
  int percent_ = -1, last_tenth_ = 0;
  double fraction_ = 0.0;
  std::chrono::steady_clock::time_point stage_start_;
};

// The command as typed, for --summary.
std::string command_line(int argc, char** argv) {
  std::string command = "sss-reference";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  return command;
}

void print_stats(const reference::ReferenceStats& s) {
  if (s.spp > 0 || s.probes > 0) {  // the probe estimator
    std::fprintf(stderr,
                 "sss-reference: probe estimator, %llu batches per pixel over %llu subsurface pixels (%d passes), "
                 "relative standard error %.4g\n",
                 (unsigned long long)s.spp, (unsigned long long)s.subsurface_pixels, s.passes, s.relative_standard_error);
    std::fprintf(stderr, "  %llu probe rays, %llu hits, %llu shadow rays; %.4g probes/s\n",
                 (unsigned long long)s.probes, (unsigned long long)s.hits, (unsigned long long)s.shadow_rays,
                 double(s.probes) / std::max(s.render_ms * 1e-3, 1e-9));
    std::fprintf(stderr, "  time: profiles %.0f ms, render %.0f ms, total %.0f ms\n", s.profile_ms, s.render_ms,
                 s.total_ms);
    return;
  }
  std::fprintf(stderr, "sss-reference: %zu irradiance points\n", s.points);
  for (const reference::GroupStats& g : s.groups)
    std::fprintf(stderr, "  %-24s %9zu points, spacing %.3f mm, area %.1f mm^2, %zu octree nodes\n",
                 g.material.c_str(), g.points, g.spacing_mm, g.area_mm2, g.octree.nodes);
  std::fprintf(stderr,
               "  time: profiles %.0f ms, points %.0f ms, irradiance %.0f ms, octree %.0f ms, "
               "render %.0f ms, total %.0f ms\n",
               s.profile_ms, s.sampling_ms, s.irradiance_ms, s.octree_ms, s.render_ms, s.total_ms);
}

void print_stats(const reference::GroundTruthStats& s, int threads) {
  const reference::WalkStats& w = s.walk;
  const double walk_s = std::max(s.seconds - s.setup_seconds, 1e-9);
  std::fprintf(stderr,
               "sss-reference: random walk, %llu samples per pixel over %llu subsurface pixels (%d passes), "
               "relative standard error %.4g\n",
               (unsigned long long)s.spp, (unsigned long long)s.subsurface_pixels, s.passes, s.relative_standard_error);
  std::fprintf(stderr,
               "  %llu paths, %llu scattering events (%.1f per path), %llu boundary reflections, %llu direct beams\n",
               (unsigned long long)w.paths, (unsigned long long)w.scattering_events,
               w.paths ? double(w.scattering_events) / double(w.paths) : 0.0, (unsigned long long)w.boundary_hits,
               (unsigned long long)w.beams);
  std::fprintf(stderr, "  %.4g paths/s, %.4g events/s on %d threads; escaped %llu, truncated %llu; beam BVH %zu chunks\n",
               double(w.paths) / walk_s, double(w.scattering_events) / walk_s, threads,
               (unsigned long long)w.escaped, (unsigned long long)w.truncated, s.beam_chunks);
  std::fprintf(stderr, "  time: setup %.2f s, walk %.2f s, total %.2f s\n", s.setup_seconds, walk_s, s.seconds);
}

// An output folder that is not there fails now rather than after a long render (the
// write itself still reports every other failure).
bool folders_exist(const std::vector<const std::string*>& files) {
  for (const std::string* file : files) {
    if (file->empty()) continue;
    const std::filesystem::path parent = std::filesystem::path(*file).parent_path();
    std::error_code ec;
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
      std::cerr << "sss-reference: error: " << *file << ": the folder " << parent.string()
                << " does not exist or is not a folder\n";
      return false;
    }
  }
  return true;
}

// The command line without what does not change the pixels: the tile's settings
// fingerprint (TileMerge.h), equal for every tile of one render.
std::string pixel_settings(int argc, char** argv) {
  static const char* const kWithValue[] = {"--out", "--png", "--variance", "--tile", "--threads", "--exposure", "--summary"};
  static const char* const kFlags[] = {"--quiet", "--stats"};
  std::string out;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    bool skip = false;
    for (const char* o : kWithValue) {
      if (a == o) {
        ++i;
        skip = true;
      } else if (a.rfind(std::string(o) + "=", 0) == 0) {
        skip = true;
      }
    }
    for (const char* f : kFlags) skip = skip || a == f;
    if (skip) continue;
    out += (out.empty() ? "" : " ") + a;
  }
  return out;
}

// What every --summary of the two per-pixel Monte Carlo renderers (the probe estimator and
// the ground truth) says alike: the command, the pixels' settings, the size, and how far
// the passes went. Each adds its own counts.
template <class Stats>
nlohmann::json summary_common(int argc, char** argv, const std::string& settings, int width, int height,
                              const Stats& stats, int threads) {
  return {{"command", command_line(argc, argv)},
          {"settings", settings},
          {"width", width},
          {"height", height},
          {"spp", stats.spp},
          {"passes", stats.passes},
          {"relative_standard_error", stats.relative_standard_error},
          {"subsurface_pixels", stats.subsurface_pixels},
          {"threads", threads}};
}

int merge_usage(const std::string& message) { return usage_error("sss-reference merge", message); }

int merge_main(int argc, char** argv) {
  CLI::App app{"sss-reference merge: put the tiles of one random-walk or probe render (--tile K/N) back together into the "
               "frame and its variance, bit for bit what one process renders",
               "sss-reference merge"};
  std::vector<std::string> tiles;
  std::string out, variance, png;
  float exposure = 1.0f;
  app.add_option("tiles", tiles, "The mean and variance EXRs of every tile, in any order")->required();
  app.add_option("--out", out, "The frame: FILE.exr")->required();
  app.add_option("--variance", variance, "Its variance of the mean: FILE.exr");
  app.add_option("--png", png, "Also the tonemapped frame as a PNG");
  app.add_option("--exposure", exposure, "Exposure of the PNG (default 1)");
  if (const auto stop = parse_command_line(app, argc, argv, "sss-reference merge")) return *stop;
  if (lower_extension(out) != ".exr") return merge_usage("--out: expected a .exr file name, got '" + out + "'");
  if (!variance.empty() && lower_extension(variance) != ".exr")
    return merge_usage("--variance: expected a .exr file name, got '" + variance + "'");
  if (!png.empty() && lower_extension(png) != ".png") return merge_usage("--png: expected a .png file name, got '" + png + "'");
  if (!(std::isfinite(exposure) && exposure > 0.0f))
    return merge_usage("--exposure: expected a finite number > 0, got " + message_number(exposure));
  for (const std::string& t : tiles)
    for (const std::string* o : {&out, &variance, &png})
      if (!o->empty() && std::filesystem::weakly_canonical(t) == std::filesystem::weakly_canonical(*o))
        return merge_usage(*o + " is one of the tiles; write the frame elsewhere");
  if (!variance.empty() && std::filesystem::weakly_canonical(variance) == std::filesystem::weakly_canonical(out))
    return merge_usage("--variance: the same file as --out");
  if (!png.empty() && std::filesystem::weakly_canonical(png) == std::filesystem::weakly_canonical(out))
    return merge_usage("--png: the same file as --out");
  if (!folders_exist({&out, &variance, &png})) return kExitRuntime;
  auto merged = reference::merge_tiles(tiles);
  if (auto* e = std::get_if<std::string>(&merged)) return merge_usage(*e);
  const reference::MergedFrame& f = std::get<reference::MergedFrame>(merged);
  try {
    image::write_exr(out, f.mean);
    if (!variance.empty()) image::write_exr(variance, f.variance);
    if (!png.empty()) image::write_png(png, image::tonemap(f.mean, exposure));
  } catch (const std::exception& e) {
    std::cerr << "sss-reference: error: " << e.what() << '\n';
    return kExitRuntime;
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "merge") == 0) return merge_main(argc - 1, argv + 1);
  CLI::App app{
      "sss-reference: offline CPU references for subsurface scattering. --method diffusion (default): Jensen & "
      "Buhler 2002's irradiance points and octree with the exact diffusion profile (no Gaussian fit), or with "
      "--estimator probe a per-pixel Monte Carlo estimate of the same integral that converges to it. --method "
      "random-walk: the ground truth, volumetric light transport through the scene's meshes (σa, σs, g, η; "
      "smooth dielectric boundary). 'sss-reference merge --help' puts tiles together.",
      "sss-reference"};
  std::string scene_name = std::string(scene::kDefaultScene);
  std::string out, png, method = "diffusion", estimator = "auto", variance, tile_text, summary;
  std::string kernel = "exact", shadows = "ray-traced", transmission = "profile", thickness = "ray-cast";
  int width = 640, height = 360, threads = 0, shadow_map_size = 1024;
  double spacing = 0.5, error_bound = 0.3, target_error = 0.0;
  std::size_t max_points = 8'000'000;
  std::uint64_t seed = 1, spp = 0;
  float exposure = 1.0f;
  std::string fresnel = "off";
  std::string single_scattering = "on";
  bool brute = false, diffuse_only = false, no_specular = false, quiet = false, stats = false, exitance = false;
  MaterialOverrideArgs material;
  EnvironmentArgs environment;
  app.add_option("scene", scene_name, "A glTF/GLB file or builtin:NAME (default builtin:bunny)");
  app.add_option("--out", out, "Output: FILE.exr (linear radiance) or FILE.png (tonemapped)")->required();
  app.add_option("--png", png, "Also write the tonemapped image to this PNG");
  app.add_option("--width", width, "Image width (default 640)")->check(CLI::Range(1, 16384));
  app.add_option("--height", height, "Image height (default 360)")->check(CLI::Range(1, 16384));
  app.add_option("--method", method,
                 "diffusion (default): the exact diffusion profile over irradiance points; random-walk: the ground "
                 "truth, true transport through the meshes");
  app.add_option("--estimator", estimator,
                 "diffusion: auto (default): the octree, its points made as dense as the pixels where these are "
                 "finer (the median footprint over the frame), or the probe where that many points would exceed "
                 "--max-points; an option of one estimator picks it (--spacing... octree, --spp... probe); octree: irradiance points summed through the Jensen-Buhler octree, its "
                 "error set by --spacing and --error-bound; probe: per-pixel profile importance sampling with probe "
                 "rays, unbiased, with a standard error per pixel (--spp, --target-error, --variance)");
  add_material_override_options(app, material);
  add_environment_options(app, environment);
  app.add_option("--spacing", spacing,
                 "diffusion: irradiance point spacing in reduced mean free paths (default 0.5; lower it for "
                 "more points and a more accurate sum)");
  app.add_option("--max-points", max_points, "diffusion: refuse to spread more points than this (default 8000000)");
  app.add_option("--error-bound", error_bound,
                 "diffusion: Jensen-Buhler maximum solid angle (sr) of an octree node used whole (default 0.3; "
                 "0 descends to every point)");
  app.add_option("--kernel", kernel,
                 "diffusion: the profile summed: exact (the model's R(r), default) or fit (the material's "
                 "sum-of-Gaussians fit, exactly as the real-time renderer gets it); the error budget's "
                 "'Gaussian fit' link");
  app.add_option("--shadows", shadows,
                 "diffusion: ray-traced (a shadow ray per light, default) or shadow-map (the real-time frame's "
                 "shadow maps and 3x3 PCF rebuilt on the CPU, no shadow from point lights); the error budget's "
                 "'lighting' link");
  app.add_option("--transmission", transmission,
                 "diffusion, octree: how light crosses thin parts: profile (default: far-side points summed with "
                 "the profile, the model's own answer), local (as sss-viewer: the far side dark, each point facing "
                 "away from a light given E (-n.l) T(d) / R_d, d ray-cast towards the light, T(d) R's tail beyond "
                 "d), or off (far side dark, nothing transmitted: sss-viewer --transmission off); the error "
                 "budget's transmission link");
  app.add_option("--thickness-from", thickness,
                 "diffusion, --transmission local: the thickness d towards each light, ray-cast (default: the last "
                 "surface on the light's line) or shadow-map (read as sss-viewer reads it from the light's "
                 "unbiased shadow map at --shadow-map-size; the error budget's thickness link)");
  app.add_option("--shadow-map-size", shadow_map_size,
                 "diffusion --shadows shadow-map or --thickness-from shadow-map: texels a side (default 1024, as sss-viewer's)")
      ->check(CLI::Range(1, 16384));
  app.add_flag("--brute-force", brute, "diffusion: sum every irradiance point at every pixel (no octree)");
  app.add_option("--spp", spp,
                 "random-walk: samples per pixel; --estimator probe: batches of probes per pixel (default 24); with "
                 "--target-error: the most a pixel gets");
  app.add_option("--target-error", target_error,
                 "random-walk, --estimator probe: add samples until the frame's relative standard error is at most "
                 "this (random-walk: default 0.02 when --spp is not given)");
  app.add_option("--variance", variance,
                 "random-walk, --estimator probe: also write the per-pixel variance of the mean (FILE.exr)");
  app.add_option("--tile", tile_text,
                 "random-walk, --estimator probe: render tile K of N (rows y with y mod N = K-1) for "
                 "'sss-reference merge'; needs --spp and --variance");
  app.add_option("--summary", summary,
                 "random-walk, --estimator probe: also write what the render did as JSON (command, samples per pixel, "
                 "relative standard error, paths or probes, times)");
  app.add_flag("--exitance", exitance,
               "random-walk: write M/pi, the cosine-weighted mean radiance leaving each visible point (the "
               "quantity --diffuse-only writes with --method diffusion), instead of the radiance towards the eye");
  app.add_flag("--diffuse-only", diffuse_only,
               "Write only the light that crossed a medium, before the albedo (diffusion: M/pi; no specular, "
               "opaque surfaces black)");
  app.add_option("--threads", threads, "Worker threads (default 0: all cores)")->check(CLI::Range(0, 1024));
  app.add_option("--seed", seed, "Seed of the point sets or of the walks (default 1)");
  app.add_option("--exposure", exposure, "Exposure of the PNG (default 1)");
  app.add_option("--fresnel", fresnel,
                 "diffusion, on | off: directional Fresnel factors on subsurface light, as sss-viewer --fresnel "
                 "(default off); the random walk refracts at the faces whatever this says");
  app.add_option("--single-scattering", single_scattering,
                 "diffusion, on | off: S(1) marched along the refracted eye ray (Jensen et al. 2001, the real g), "
                 "unblurred, with profiles that leave their own once-scattered light out, as sss-viewer "
                 "--single-scattering (default on); the random walk has it by construction");
  app.add_flag("--no-specular", no_specular,
               "diffusion, EXR --out: write the frame less its specular term (and S(1) with --single-scattering on, "
               "the unblurred part), the light that scattered (with its "
               "albedo) and the opaque diffuse; compare with sss-viewer --no-specular (the error budget's "
               "scattered light)");
  app.add_flag("--quiet", quiet, "No progress bar");
  app.add_flag("--stats", stats, "Print counts, rates and stage times on stderr");
  // CLI11 wraps "-1" to 2^64 - 1 for an unsigned option.
  for (const char* name : {"--seed", "--spp"})
    app.get_option(name)->check(CLI::Validator(
        [](std::string& v) {
          return v.find('-') == std::string::npos ? std::string() : "expected a number >= 0, got '" + v + "'";
        },
        "UINT"));
  if (const auto stop = parse_command_line(app, argc, argv, "sss-reference")) return *stop;
  // Each side is capped at 16384 by its check; the product at what image files are read
  // back with (image::kMaxImagePixels).
  if (std::uint64_t(width) * std::uint64_t(height) > image::kMaxImagePixels)
    return usage("--width x --height: at most " + std::to_string(image::kMaxImagePixels) +
                 " pixels, got " + std::to_string(width) + " x " + std::to_string(height));
  if (method != "diffusion" && method != "random-walk")
    return usage("--method: expected diffusion or random-walk, got '" + method + "'");
  const bool walk = method == "random-walk";
  if (estimator != "auto" && estimator != "octree" && estimator != "probe")
    return usage("--estimator: expected auto, octree or probe, got '" + estimator + "'");
  if (walk && app.count("--estimator") > 0) return usage("--estimator: applies to --method diffusion only");
  if (fresnel != "on" && fresnel != "off") return usage("--fresnel: expected on or off, got '" + fresnel + "'");
  if (single_scattering != "on" && single_scattering != "off")
    return usage("--single-scattering: expected on or off, got '" + single_scattering + "'");
  if (walk && app.count("--single-scattering") > 0)
    return usage("--single-scattering: applies to --method diffusion only (the random walk scatters once by construction)");
  if (walk && app.count("--fresnel") > 0)
    return usage("--fresnel: applies to --method diffusion only (the random walk refracts at the faces)");
  // auto: what the options ask for, or (neither asked) the frame decides after loading.
  if (!walk && estimator == "auto") {
    bool wants_probe = false, wants_octree = false;
    for (const char* name : {"--spp", "--target-error", "--variance", "--summary", "--tile"})
      wants_probe = wants_probe || app.count(name) > 0;
    for (const char* name : {"--spacing", "--max-points", "--error-bound", "--brute-force", "--transmission",
                             "--thickness-from"})
      wants_octree = wants_octree || app.count(name) > 0;
    if (wants_octree) estimator = "octree";  // with probe options too: refused below, naming them
    else if (wants_probe) estimator = "probe";
  }
  const bool choose_later = !walk && estimator == "auto";
  bool probe = !walk && estimator == "probe";
  if (kernel != "exact" && kernel != "fit") return usage("--kernel: expected exact or fit, got '" + kernel + "'");
  if (shadows != "ray-traced" && shadows != "shadow-map")
    return usage("--shadows: expected ray-traced or shadow-map, got '" + shadows + "'");
  if (transmission != "profile" && transmission != "local" && transmission != "off")
    return usage("--transmission: expected profile, local or off, got '" + transmission + "'");
  if (app.count("--transmission") > 0 && (walk || probe))
    return usage("--transmission: applies to --method diffusion with --estimator octree only");
  if (thickness != "ray-cast" && thickness != "shadow-map")
    return usage("--thickness-from: expected ray-cast or shadow-map, got '" + thickness + "'");
  if (app.count("--thickness-from") > 0 && transmission != "local")
    return usage("--thickness-from: applies to --transmission local only (the other transmissions use no thickness)");
  for (const char* name : {"--kernel", "--shadows", "--shadow-map-size"})
    if (app.count(name) > 0 && walk)
      return usage(std::string(name) + ": applies to --method diffusion only (the ground truth has neither a "
                                       "profile nor shadow maps)");
  if (app.count("--shadow-map-size") > 0 && shadows != "shadow-map" && thickness != "shadow-map")
    return usage("--shadow-map-size: applies to --shadows shadow-map or --thickness-from shadow-map only");
  for (const char* name : {"--spacing", "--max-points", "--error-bound", "--brute-force"})
    if (app.count(name) > 0 && (walk || probe))
      return usage(std::string(name) + ": applies to --method diffusion with --estimator octree only");
  if (app.count("--exitance") > 0 && !walk) return usage("--exitance: applies to --method random-walk only");
  for (const char* name : {"--spp", "--target-error", "--variance", "--summary", "--tile"})
    if (app.count(name) > 0 && !walk && !probe)
      return usage(std::string(name) + ": applies to --method random-walk or --estimator probe only");
  if (!(std::isfinite(spacing) && spacing > 0.0))
    return usage("--spacing: expected a finite number > 0 (mean free paths), got " + message_number(spacing));
  if (max_points == 0) return usage("--max-points: expected a number >= 1, got 0");
  if (!(std::isfinite(error_bound) && error_bound >= 0.0))
    return usage("--error-bound: expected a finite number >= 0 (sr), got " + message_number(error_bound));
  if (!(std::isfinite(exposure) && exposure > 0.0f))
    return usage("--exposure: expected a finite number > 0, got " + message_number(exposure));
  if (app.count("--spp") > 0 && spp == 0) return usage("--spp: expected a number of samples per pixel >= 1, got 0");
  if (app.count("--target-error") > 0 && !(std::isfinite(target_error) && target_error > 0.0 && target_error < 1.0))
    return usage("--target-error: expected a relative standard error in (0, 1), got " + message_number(target_error));
  if (walk && spp == 0 && target_error == 0.0) target_error = 0.02;
  if (probe && spp == 0 && target_error == 0.0) spp = reference::kDefaultProbeBatches;  // its comment: why 24
  if (app.count("--target-error") > 0 && spp == 1)
    return usage("--spp: a target error needs at least 2 samples per pixel to measure the noise, got 1");
  reference::TileSpec tile;
  if (!tile_text.empty()) {
    std::string why;
    const auto parsed = reference::parse_tile(tile_text, why);
    if (!parsed) return usage("--tile: " + why);
    tile = *parsed;
    if (app.count("--spp") == 0 || app.count("--target-error") > 0)
      return usage("--tile: tiles need a fixed --spp (a target error is a property of the whole frame)");
    if (variance.empty()) return usage("--tile: a tile needs --variance FILE.exr too (merge puts both together)");
    if (tile.count > std::uint32_t(height))
      return usage("--tile: " + std::to_string(tile.count) + " tiles of interleaved rows need --height >= " +
                   std::to_string(tile.count) + ", got " + std::to_string(height));
  }
  const std::string ext = lower_extension(out);
  if (ext != ".exr" && ext != ".png") return usage("--out: expected a .exr or .png file name, got '" + out + "'");
  if (!tile.whole() && ext != ".exr") return usage("--out: a tile is written as .exr (merge reads linear values), got '" + out + "'");
  if (no_specular) {
    if (walk)
      return usage("--no-specular: applies to --method diffusion only (the ground truth's specular is not a "
                   "separate term; take off the diffusion reference's, as the error budget does)");
    if (diffuse_only) return usage("--no-specular: --diffuse-only already has no specular");
    if (ext != ".exr") return usage("--no-specular: writes linear values, --out must be a .exr file, got '" + out + "'");
    if (!png.empty()) return usage("--no-specular: --png would still show the specular; leave it out");
  }
  if (!png.empty() && lower_extension(png) != ".png") return usage("--png: expected a .png file name, got '" + png + "'");
  if (!variance.empty() && lower_extension(variance) != ".exr")
    return usage("--variance: expected a .exr file name, got '" + variance + "'");
  if (!summary.empty() && lower_extension(summary) != ".json")
    return usage("--summary: expected a .json file name, got '" + summary + "'");
  {
    const std::pair<const char*, const std::string*> files[] = {
        {"--out", &out}, {"--png", &png}, {"--variance", &variance}, {"--summary", &summary}};
    for (std::size_t i = 0; i < std::size(files); ++i)
      for (std::size_t j = i + 1; j < std::size(files); ++j)
        if (!files[i].second->empty() && !files[j].second->empty() &&
            std::filesystem::weakly_canonical(*files[i].second) == std::filesystem::weakly_canonical(*files[j].second))
          return usage(std::string(files[j].first) + ": '" + *files[j].second + "' is the same file as " +
                       files[i].first);
  }
  if (!folders_exist({&out, &png, &variance, &summary})) return kExitRuntime;

  auto loaded = scene::load_scene(scene_name);
  if (auto* e = std::get_if<scene::LoadError>(&loaded)) return input_error("sss-reference", e->what());
  scene::Scene s = std::move(std::get<scene::Scene>(loaded));
  scene::add_camera_if_missing(s);
  scene::add_light_if_missing(s);
  auto overridden = apply_material_overrides(s, material);
  if (auto* e = std::get_if<FieldError>(&overridden)) return usage(e->what());
  if (auto e = apply_environment(s, environment))
    return e->file ? input_error("sss-reference", e->message) : usage(e->message);

  add_material_warnings(s, std::uint32_t(height));
  print_messages("sss-reference", "warning", s.warnings);

  // What the diffusion reference renders with (the auto choice below reads its size, spacing,
  // point cap and threads, and sets its spacing).
  reference::ReferenceOptions diffusion;
  diffusion.width = std::uint32_t(width);
  diffusion.height = std::uint32_t(height);
  diffusion.spacing_mfp = spacing;
  diffusion.max_points = max_points;
  diffusion.max_solid_angle = error_bound;
  diffusion.brute_force = brute;
  diffusion.diffuse_only = diffuse_only;
  diffusion.fresnel = fresnel == "on";
  diffusion.single_scattering = single_scattering == "on";
  diffusion.threads = threads;
  diffusion.seed = seed;
  diffusion.exposure = exposure;
  diffusion.kernel = kernel == "fit" ? reference::KernelSource::Fit : reference::KernelSource::Exact;
  diffusion.shadows = shadows == "shadow-map" ? reference::Shadows::ShadowMap : reference::Shadows::RayTraced;
  diffusion.shadow_map_size = std::uint32_t(shadow_map_size);
  diffusion.thickness = thickness == "shadow-map" ? reference::Thickness::ShadowMap : reference::Thickness::RayCast;
  diffusion.transmission = transmission == "local" ? reference::Transmission::Local
                           : transmission == "off" ? reference::Transmission::Off
                                                   : reference::Transmission::Profile;
  if (choose_later) {
    reference::EstimatorChoice choice;
    try {
      choice = reference::choose_estimator(s, diffusion);
    } catch (const std::invalid_argument& e) {
      return usage(e.what());
    } catch (const std::exception& e) {
      std::cerr << "sss-reference: error: " << e.what() << '\n';
      return kExitRuntime;
    }
    probe = choice.estimator == reference::Estimator::Probe;
    if (probe) spp = reference::kDefaultProbeBatches;
    if (!quiet)
      std::cerr << "sss-reference: note: --estimator auto chose " << reference::describe(choice, spacing)
                << "; --estimator octree|probe to choose\n";
    diffusion = reference::with_choice(diffusion, choice);
  }
  const int used_threads = threads > 0 ? threads : int(std::thread::hardware_concurrency());
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  ProgressBar bar(!quiet);
  auto progress = [&](const char* stage, double f) { bar(stage, f); };
  try {
    if (!walk) {
      reference::ReferenceOptions o = diffusion;
      if (probe) {
        o.estimator = reference::Estimator::Probe;
        o.spp = spp;
        o.target_error = target_error;
        o.tile = tile;
        if (spp == 1)
          std::cerr << "sss-reference: warning: --spp 1: one batch per pixel says nothing of the noise; the "
                       "variance is written as 0 and the relative standard error is unknown (nan)\n";
      }
      reference::ReferenceImage r = reference::render_reference(s, o, progress, &g_cancel);
      if (g_cancel.load()) throw reference::Cancelled();
      if (probe) {
        const std::string settings = pixel_settings(argc, argv);
        const double error = r.stats.relative_standard_error;
        const std::string tile_name = tile.whole() ? "" : tile_text;
        r.hdr.attributes = reference::ground_truth_attributes("mean", tile_name, settings, r.stats.spp, error);
        r.variance.attributes = reference::ground_truth_attributes("variance", tile_name, settings, r.stats.spp, error);
      }
      if (no_specular) image::write_exr(out, image::subtract_rgb(r.hdr, r.specular));
      else if (ext == ".exr") image::write_exr(out, r.hdr);
      else image::write_png(out, r.display);
      if (!variance.empty()) image::write_exr(variance, r.variance);
      if (!png.empty()) image::write_png(png, r.display);
      if (!summary.empty()) {
        nlohmann::json j = summary_common(argc, argv, pixel_settings(argc, argv), width, height, r.stats, used_threads);
        j.update({{"method", "diffusion"},
                  {"estimator", "probe"},
                  {"kernel", kernel},
                  {"shadows", shadows},
                  {"probes", r.stats.probes},
                  {"hits", r.stats.hits},
                  {"shadow_rays", r.stats.shadow_rays},
                  {"seconds", r.stats.total_ms * 1e-3}});
        image::write_file_atomically(summary, j.dump(2) + "\n");
      }
      if (stats) print_stats(r.stats);
    } else {
      reference::GroundTruthOptions o;
      o.width = std::uint32_t(width);
      o.height = std::uint32_t(height);
      o.spp = spp;
      o.target_error = target_error;
      o.diffuse_only = diffuse_only;
      o.exitance = exitance;
      o.threads = threads;
      o.seed = seed;
      o.exposure = exposure;
      o.tile = tile;
      o.on_warning = [](const std::string& w) { std::cerr << "sss-reference: warning: " << w << '\n'; };
      if (spp == 1)
        std::cerr << "sss-reference: warning: --spp 1: one sample per pixel says nothing of the noise; the "
                     "variance is written as 0 and the relative standard error is unknown (nan)\n";
      reference::GroundTruthImage r = reference::render_ground_truth(s, o, progress, &g_cancel);
      if (g_cancel.load()) throw reference::Cancelled();
      const std::string settings = pixel_settings(argc, argv);
      const std::string tile_name = tile.whole() ? "" : tile_text;
      const double error = r.stats.relative_standard_error;
      r.hdr.attributes = reference::ground_truth_attributes("mean", tile_name, settings, r.stats.spp, error);
      r.variance.attributes = reference::ground_truth_attributes("variance", tile_name, settings, r.stats.spp, error);
      if (ext == ".exr") image::write_exr(out, r.hdr);
      else image::write_png(out, r.display);
      if (!variance.empty()) image::write_exr(variance, r.variance);
      if (!png.empty()) image::write_png(png, r.display);
      if (!summary.empty()) {
        const reference::WalkStats& w = r.stats.walk;
        nlohmann::json j = summary_common(argc, argv, settings, width, height, r.stats, used_threads);
        j.update({{"paths", w.paths},
                  {"scattering_events", w.scattering_events},
                  {"boundary_reflections", w.boundary_hits},
                  {"direct_beams", w.beams},
                  {"escaped", w.escaped},
                  {"truncated", w.truncated},
                  {"setup_seconds", r.stats.setup_seconds},
                  {"seconds", r.stats.seconds},
                  {"warnings", r.stats.warnings}});
        image::write_file_atomically(summary, j.dump(2) + "\n");
      }
      if (stats) print_stats(r.stats, used_threads);
    }
  } catch (const reference::Cancelled&) {
    const int sig = g_signal.load();
    std::cerr << "\nsss-reference: interrupted" << (sig == SIGTERM ? " (SIGTERM)" : "")
              << "; nothing was written\n";
    return sig == SIGTERM ? 128 + SIGTERM : kExitInterrupted;
  } catch (const std::invalid_argument& e) {
    return usage(e.what());
  } catch (const std::exception& e) {
    std::cerr << "sss-reference: error: " << e.what() << '\n';
    return kExitRuntime;
  }
  return kExitOk;
}
