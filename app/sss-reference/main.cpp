// sss-reference: the offline CPU renderers (DESIGN.md §4, §6).
//   sss-reference SCENE --out FILE.exr [--method diffusion|random-walk] ...
//   sss-reference merge TILE.exr... --out FILE.exr [--variance FILE.exr]
// --method diffusion (default): the Jensen–Buhler reference with the exact diffusion
// profile. --method random-walk: the ground truth, volumetric transport through the
// scene's meshes (reference/GroundTruth.h), with its variance, a sample count or
// a target error, and tiles that `merge` puts together.
// Errors exit 2 (usage, input) or 1 (runtime); Ctrl-C (SIGTERM) stops the render, writes
// nothing and exits 130 (143).
#include "CliSupport.h"
#include "EnvironmentArgs.h"
#include "MaterialOverrides.h"
#include "SceneArgs.h"
#include "Merge.h"
#include "Report.h"

#include "image/AtomicFile.h"
#include "image/Image.h"
#include "image/Tonemap.h"
#include "reference/GroundTruth.h"
#include "reference/ReferenceRenderer.h"
#include "reference/TileMerge.h"
#include "scene/BuiltinScenes.h"

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
#include <functional>
#include <iostream>
#include <optional>
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

// The command as typed, for --summary.
std::string command_line(int argc, char** argv) {
  std::string command = "sss-reference";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  return command;
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

// Everything the command line says, and what check_modes and check_files derive from it.
struct Args {
  std::string scene_name = std::string(scene::kDefaultScene);
  std::string out, png, method = "diffusion", estimator = "auto", variance, tile_text, summary;
  std::string kernel = "exact", shadows = "ray-traced", transmission = "profile", thickness = "ray-cast";
  std::string sky_occlusion = "on";  // --sky-occlusion (the GPU-shadow mode)
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
  // Derived.
  bool walk = false;          // --method random-walk
  bool probe = false;         // the diffusion reference's probe estimator
  bool choose_later = false;  // --estimator auto with neither kind's options: the frame decides
  reference::TileSpec tile;
  std::string ext;            // --out's, lower case
};

// The diffusion reference's own options: the octree's points, the profile summed, and
// the error budget's lighting, transmission and thickness links.
void add_diffusion_options(CLI::App& app, Args& a) {
  app.add_option("--spacing", a.spacing,
                 "diffusion: irradiance point spacing in reduced mean free paths (default 0.5; lower it for "
                 "more points and a more accurate sum)");
  app.add_option("--max-points", a.max_points, "diffusion: refuse to spread more points than this (default 8000000)");
  app.add_option("--error-bound", a.error_bound,
                 "diffusion: Jensen-Buhler maximum solid angle (sr) of an octree node used whole (default 0.3; "
                 "0 descends to every point)");
  app.add_option("--kernel", a.kernel,
                 "diffusion: the profile summed: exact (the model's R(r), default) or fit (the material's "
                 "sum-of-Gaussians fit, exactly as the real-time renderer gets it); the error budget's "
                 "'Gaussian fit' link");
  app.add_option("--shadows", a.shadows,
                 "diffusion: ray-traced (a shadow ray per light, default) or shadow-map (the real-time frame's "
                 "shadow maps and 3x3 PCF rebuilt on the CPU, no shadow from point lights); the error budget's "
                 "'lighting' link");
  app.add_option("--sky-occlusion", a.sky_occlusion,
                 "diffusion --shadows shadow-map with --environment: on (default) takes away the sky the scene "
                 "blocks as sss-viewer --sky-occlusion does (its per-vertex bake, interpolated), off leaves every "
                 "point the whole sky; ray-traced shadows sample the sky's occlusion itself");
  app.add_option("--transmission", a.transmission,
                 "diffusion, octree: how light crosses thin parts: profile (default: far-side points summed with "
                 "the profile, the model's own answer), local (as sss-viewer: the far side dark, each point facing "
                 "away from a light given E (-n.l) T(d) / R_d, d ray-cast towards the light, T(d) R's tail beyond "
                 "d; with --environment also the sky behind each point, through its inward thickness along -n), or "
                 "off (far side dark, nothing transmitted: sss-viewer --transmission off); the error "
                 "budget's transmission link");
  app.add_option("--thickness-from", a.thickness,
                 "diffusion, --transmission local: the thickness d towards each light, ray-cast (default: the last "
                 "surface on the light's line) or shadow-map (read as sss-viewer reads it from the light's "
                 "unbiased shadow map at --shadow-map-size, and the sky's inward thickness from its per-vertex "
                 "bake; the error budget's thickness link)");
  app.add_option("--shadow-map-size", a.shadow_map_size,
                 "diffusion --shadows shadow-map or --thickness-from shadow-map: texels a side (default 1024, as sss-viewer's)")
      ->check(CLI::Range(1, 16384));
  app.add_flag("--brute-force", a.brute, "diffusion: sum every irradiance point at every pixel (no octree)");
}

// The per-pixel Monte Carlo options (the random walk, the probe estimator): samples, the
// target error, the variance, tiles and the summary.
void add_sampling_options(CLI::App& app, Args& a) {
  app.add_option("--spp", a.spp,
                 "random-walk: samples per pixel; --estimator probe: batches of probes per pixel (default 24); with "
                 "--target-error: the most a pixel gets");
  app.add_option("--target-error", a.target_error,
                 "random-walk, --estimator probe: add samples until the frame's relative standard error is at most "
                 "this (random-walk: default 0.02 when --spp is not given)");
  app.add_option("--variance", a.variance,
                 "random-walk, --estimator probe: also write the per-pixel variance of the mean (FILE.exr)");
  app.add_option("--tile", a.tile_text,
                 "random-walk, --estimator probe: render tile K of N (rows y with y mod N = K-1) for "
                 "'sss-reference merge'; needs --spp and --variance");
  app.add_option("--summary", a.summary,
                 "random-walk, --estimator probe: also write what the render did as JSON (command, samples per pixel, "
                 "relative standard error, paths or probes, times)");
  app.add_flag("--exitance", a.exitance,
               "random-walk: write M/pi, the cosine-weighted mean radiance leaving each visible point (the "
               "quantity --diffuse-only writes with --method diffusion), instead of the radiance towards the eye");
}

void add_options(CLI::App& app, Args& a) {
  app.add_option("scene", a.scene_name, "A glTF/GLB file or builtin:NAME (default builtin:bunny)");
  app.add_option("--out", a.out, "Output: FILE.exr (linear radiance) or FILE.png (tonemapped)")->required();
  app.add_option("--png", a.png, "Also write the tonemapped image to this PNG");
  app.add_option("--width", a.width, "Image width (default 640)")->check(CLI::Range(1, 16384));
  app.add_option("--height", a.height, "Image height (default 360)")->check(CLI::Range(1, 16384));
  app.add_option("--method", a.method,
                 "diffusion (default): the exact diffusion profile over irradiance points; random-walk: the ground "
                 "truth, true transport through the meshes");
  app.add_option("--estimator", a.estimator,
                 "diffusion: auto (default): the octree, its points made as dense as the pixels where these are "
                 "finer (the median footprint over the frame), or the probe where that many points would exceed "
                 "--max-points; an option of one estimator picks it (--spacing... octree, --spp... probe); octree: irradiance points summed through the Jensen-Buhler octree, its "
                 "error set by --spacing and --error-bound; probe: per-pixel profile importance sampling with probe "
                 "rays, unbiased, with a standard error per pixel (--spp, --target-error, --variance)");
  add_material_override_options(app, a.material);
  add_environment_options(app, a.environment);
  add_diffusion_options(app, a);
  add_sampling_options(app, a);
  app.add_flag("--diffuse-only", a.diffuse_only,
               "Write only the light that crossed a medium, before the albedo (diffusion: M/pi; no specular, "
               "opaque surfaces black)");
  app.add_option("--threads", a.threads, "Worker threads (default 0: all cores)")->check(CLI::Range(0, 1024));
  app.add_option("--seed", a.seed, "Seed of the point sets or of the walks (default 1)");
  app.add_option("--exposure", a.exposure, "Exposure of the PNG (default 1)");
  app.add_option("--fresnel", a.fresnel,
                 "diffusion, on | off: directional Fresnel factors on subsurface light, as sss-viewer --fresnel "
                 "(default off); the random walk refracts at the faces whatever this says");
  app.add_option("--single-scattering", a.single_scattering,
                 "diffusion, on | off: S(1) marched along the refracted eye ray (Jensen et al. 2001, the real g), "
                 "unblurred, with profiles that leave their own once-scattered light out, as sss-viewer "
                 "--single-scattering (default on); the random walk has it by construction");
  app.add_flag("--no-specular", a.no_specular,
               "diffusion, EXR --out: write the frame less its specular term (and S(1) with --single-scattering on, "
               "the unblurred part), the light that scattered (with its "
               "albedo) and the opaque diffuse; compare with sss-viewer --no-specular (the error budget's "
               "scattered light)");
  app.add_flag("--quiet", a.quiet, "No progress bar");
  app.add_flag("--stats", a.stats, "Print counts, rates and stage times on stderr");
  // CLI11 wraps "-1" to 2^64 - 1 for an unsigned option.
  for (const char* name : {"--seed", "--spp"})
    app.get_option(name)->check(CLI::Validator(
        [](std::string& v) {
          return v.find('-') == std::string::npos ? std::string() : "expected a number >= 0, got '" + v + "'";
        },
        "UINT"));
}

// --method, --estimator and the options that belong to one of them; an exit status where
// they do not fit together.
std::optional<int> check_modes(const CLI::App& app, Args& a) {
  if (a.method != "diffusion" && a.method != "random-walk")
    return usage("--method: expected diffusion or random-walk, got '" + a.method + "'");
  a.walk = a.method == "random-walk";
  if (a.estimator != "auto" && a.estimator != "octree" && a.estimator != "probe")
    return usage("--estimator: expected auto, octree or probe, got '" + a.estimator + "'");
  if (a.walk && app.count("--estimator") > 0) return usage("--estimator: applies to --method diffusion only");
  if (a.fresnel != "on" && a.fresnel != "off") return usage("--fresnel: expected on or off, got '" + a.fresnel + "'");
  if (a.single_scattering != "on" && a.single_scattering != "off")
    return usage("--single-scattering: expected on or off, got '" + a.single_scattering + "'");
  if (a.walk && app.count("--single-scattering") > 0)
    return usage("--single-scattering: applies to --method diffusion only (the random walk scatters once by construction)");
  if (a.walk && app.count("--fresnel") > 0)
    return usage("--fresnel: applies to --method diffusion only (the random walk refracts at the faces)");
  // auto: what the options ask for, or (neither asked) the frame decides after loading.
  if (!a.walk && a.estimator == "auto") {
    bool wants_probe = false, wants_octree = false;
    for (const char* name : {"--spp", "--target-error", "--variance", "--summary", "--tile"})
      wants_probe = wants_probe || app.count(name) > 0;
    for (const char* name : {"--spacing", "--max-points", "--error-bound", "--brute-force", "--transmission",
                             "--thickness-from"})
      wants_octree = wants_octree || app.count(name) > 0;
    if (wants_octree) a.estimator = "octree";  // with probe options too: refused below, naming them
    else if (wants_probe) a.estimator = "probe";
  }
  a.choose_later = !a.walk && a.estimator == "auto";
  a.probe = !a.walk && a.estimator == "probe";
  if (a.kernel != "exact" && a.kernel != "fit") return usage("--kernel: expected exact or fit, got '" + a.kernel + "'");
  if (a.shadows != "ray-traced" && a.shadows != "shadow-map")
    return usage("--shadows: expected ray-traced or shadow-map, got '" + a.shadows + "'");
  if (a.transmission != "profile" && a.transmission != "local" && a.transmission != "off")
    return usage("--transmission: expected profile, local or off, got '" + a.transmission + "'");
  if (app.count("--transmission") > 0 && (a.walk || a.probe))
    return usage("--transmission: applies to --method diffusion with --estimator octree only");
  if (a.thickness != "ray-cast" && a.thickness != "shadow-map")
    return usage("--thickness-from: expected ray-cast or shadow-map, got '" + a.thickness + "'");
  if (app.count("--thickness-from") > 0 && a.transmission != "local")
    return usage("--thickness-from: applies to --transmission local only (the other transmissions use no thickness)");
  for (const char* name : {"--kernel", "--shadows", "--shadow-map-size"})
    if (app.count(name) > 0 && a.walk)
      return usage(std::string(name) + ": applies to --method diffusion only (the ground truth has neither a "
                                       "profile nor shadow maps)");
  if (a.sky_occlusion != "on" && a.sky_occlusion != "off")
    return usage("--sky-occlusion: expected on or off, got '" + a.sky_occlusion + "'");
  if (app.count("--sky-occlusion") > 0 && (a.walk || a.shadows != "shadow-map"))
    return usage("--sky-occlusion: applies to --method diffusion --shadows shadow-map only (ray-traced shadows "
                 "sample the sky's occlusion)");
  if (app.count("--shadow-map-size") > 0 && a.shadows != "shadow-map" && a.thickness != "shadow-map")
    return usage("--shadow-map-size: applies to --shadows shadow-map or --thickness-from shadow-map only");
  for (const char* name : {"--spacing", "--max-points", "--error-bound", "--brute-force"})
    if (app.count(name) > 0 && (a.walk || a.probe))
      return usage(std::string(name) + ": applies to --method diffusion with --estimator octree only");
  if (app.count("--exitance") > 0 && !a.walk) return usage("--exitance: applies to --method random-walk only");
  for (const char* name : {"--spp", "--target-error", "--variance", "--summary", "--tile"})
    if (app.count(name) > 0 && !a.walk && !a.probe)
      return usage(std::string(name) + ": applies to --method random-walk or --estimator probe only");
  return std::nullopt;
}

// The numbers, the defaults that follow from the method, and --tile.
std::optional<int> check_values(const CLI::App& app, Args& a) {
  // Each side is capped at 16384 by its check; the product at what image files are read
  // back with (image::kMaxImagePixels).
  if (std::uint64_t(a.width) * std::uint64_t(a.height) > image::kMaxImagePixels)
    return usage("--width x --height: at most " + std::to_string(image::kMaxImagePixels) +
                 " pixels, got " + std::to_string(a.width) + " x " + std::to_string(a.height));
  if (!(std::isfinite(a.spacing) && a.spacing > 0.0))
    return usage("--spacing: expected a finite number > 0 (mean free paths), got " + message_number(a.spacing));
  if (a.max_points == 0) return usage("--max-points: expected a number >= 1, got 0");
  if (!(std::isfinite(a.error_bound) && a.error_bound >= 0.0))
    return usage("--error-bound: expected a finite number >= 0 (sr), got " + message_number(a.error_bound));
  if (!(std::isfinite(a.exposure) && a.exposure > 0.0f))
    return usage("--exposure: expected a finite number > 0, got " + message_number(a.exposure));
  if (app.count("--spp") > 0 && a.spp == 0) return usage("--spp: expected a number of samples per pixel >= 1, got 0");
  if (app.count("--target-error") > 0 && !(std::isfinite(a.target_error) && a.target_error > 0.0 && a.target_error < 1.0))
    return usage("--target-error: expected a relative standard error in (0, 1), got " + message_number(a.target_error));
  if (a.walk && a.spp == 0 && a.target_error == 0.0) a.target_error = 0.02;
  if (a.probe && a.spp == 0 && a.target_error == 0.0) a.spp = reference::kDefaultProbeBatches;  // its comment: why 24
  if (app.count("--target-error") > 0 && a.spp == 1)
    return usage("--spp: a target error needs at least 2 samples per pixel to measure the noise, got 1");
  if (!a.tile_text.empty()) {
    std::string why;
    const auto parsed = reference::parse_tile(a.tile_text, why);
    if (!parsed) return usage("--tile: " + why);
    a.tile = *parsed;
    if (app.count("--spp") == 0 || app.count("--target-error") > 0)
      return usage("--tile: tiles need a fixed --spp (a target error is a property of the whole frame)");
    if (a.variance.empty()) return usage("--tile: a tile needs --variance FILE.exr too (merge puts both together)");
    if (a.tile.count > std::uint32_t(a.height))
      return usage("--tile: " + std::to_string(a.tile.count) + " tiles of interleaved rows need --height >= " +
                   std::to_string(a.tile.count) + ", got " + std::to_string(a.height));
  }
  return std::nullopt;
}

// The output files: their kinds, that no two are one file, and that their folders exist.
std::optional<int> check_files(Args& a) {
  a.ext = lower_extension(a.out);
  if (a.ext != ".exr" && a.ext != ".png") return usage("--out: expected a .exr or .png file name, got '" + a.out + "'");
  if (!a.tile.whole() && a.ext != ".exr") return usage("--out: a tile is written as .exr (merge reads linear values), got '" + a.out + "'");
  if (a.no_specular) {
    if (a.walk)
      return usage("--no-specular: applies to --method diffusion only (the ground truth's specular is not a "
                   "separate term; take off the diffusion reference's, as the error budget does)");
    if (a.diffuse_only) return usage("--no-specular: --diffuse-only already has no specular");
    if (a.ext != ".exr") return usage("--no-specular: writes linear values, --out must be a .exr file, got '" + a.out + "'");
    if (!a.png.empty()) return usage("--no-specular: --png would still show the specular; leave it out");
  }
  if (!a.png.empty() && lower_extension(a.png) != ".png") return usage("--png: expected a .png file name, got '" + a.png + "'");
  if (!a.variance.empty() && lower_extension(a.variance) != ".exr")
    return usage("--variance: expected a .exr file name, got '" + a.variance + "'");
  if (!a.summary.empty() && lower_extension(a.summary) != ".json")
    return usage("--summary: expected a .json file name, got '" + a.summary + "'");
  {
    const std::pair<const char*, const std::string*> files[] = {
        {"--out", &a.out}, {"--png", &a.png}, {"--variance", &a.variance}, {"--summary", &a.summary}};
    for (std::size_t i = 0; i < std::size(files); ++i)
      for (std::size_t j = i + 1; j < std::size(files); ++j)
        if (!files[i].second->empty() && !files[j].second->empty() &&
            std::filesystem::weakly_canonical(*files[i].second) == std::filesystem::weakly_canonical(*files[j].second))
          return usage(std::string(files[j].first) + ": '" + *files[j].second + "' is the same file as " +
                       files[i].first);
  }
  if (!folders_exist({&a.out, &a.png, &a.variance, &a.summary})) return kExitRuntime;
  return std::nullopt;
}

// What the diffusion reference renders with (the auto choice reads its size, spacing,
// point cap and threads, and sets its spacing).
reference::ReferenceOptions diffusion_options(const Args& a) {
  reference::ReferenceOptions diffusion;
  diffusion.width = std::uint32_t(a.width);
  diffusion.height = std::uint32_t(a.height);
  diffusion.spacing_mfp = a.spacing;
  diffusion.max_points = a.max_points;
  diffusion.max_solid_angle = a.error_bound;
  diffusion.brute_force = a.brute;
  diffusion.diffuse_only = a.diffuse_only;
  diffusion.fresnel = a.fresnel == "on";
  diffusion.single_scattering = a.single_scattering == "on";
  diffusion.threads = a.threads;
  diffusion.seed = a.seed;
  diffusion.exposure = a.exposure;
  diffusion.kernel = a.kernel == "fit" ? reference::KernelSource::Fit : reference::KernelSource::Exact;
  diffusion.shadows = a.shadows == "shadow-map" ? reference::Shadows::ShadowMap : reference::Shadows::RayTraced;
  diffusion.shadow_map_size = std::uint32_t(a.shadow_map_size);
  diffusion.sky_occlusion = a.sky_occlusion == "on";
  diffusion.thickness = a.thickness == "shadow-map" ? reference::Thickness::ShadowMap : reference::Thickness::RayCast;
  diffusion.transmission = a.transmission == "local" ? reference::Transmission::Local
                           : a.transmission == "off" ? reference::Transmission::Off
                                                   : reference::Transmission::Profile;
  return diffusion;
}

// --estimator auto with neither kind's options: the frame decides (choose_estimator); an
// exit status if it cannot.
std::optional<int> choose(Args& a, const scene::Scene& s, reference::ReferenceOptions& diffusion) {
  reference::EstimatorChoice choice;
  try {
    choice = reference::choose_estimator(s, diffusion);
  } catch (const std::invalid_argument& e) {
    return usage(e.what());
  } catch (const std::exception& e) {
    std::cerr << "sss-reference: error: " << e.what() << '\n';
    return kExitRuntime;
  }
  a.probe = choice.estimator == reference::Estimator::Probe;
  if (a.probe) a.spp = reference::kDefaultProbeBatches;
  if (!a.quiet)
    std::cerr << "sss-reference: note: --estimator auto chose " << reference::describe(choice, a.spacing)
              << "; --estimator octree|probe to choose\n";
  diffusion = reference::with_choice(diffusion, choice);
  return std::nullopt;
}

using Progress = std::function<void(const char*, double)>;

void render_diffusion(const Args& a, const scene::Scene& s, const reference::ReferenceOptions& diffusion,
                      const Progress& progress, int argc, char** argv, int used_threads) {
  reference::ReferenceOptions o = diffusion;
  if (a.probe) {
    o.estimator = reference::Estimator::Probe;
    o.spp = a.spp;
    o.target_error = a.target_error;
    o.tile = a.tile;
    if (a.spp == 1)
      std::cerr << "sss-reference: warning: --spp 1: one batch per pixel says nothing of the noise; the "
                   "variance is written as 0 and the relative standard error is unknown (nan)\n";
  }
  reference::ReferenceImage r = reference::render_reference(s, o, progress, &g_cancel);
  if (g_cancel.load()) throw reference::Cancelled();
  if (a.probe) {
    const std::string settings = pixel_settings(argc, argv);
    const double error = r.stats.relative_standard_error;
    const std::string tile_name = a.tile.whole() ? "" : a.tile_text;
    r.hdr.attributes = reference::ground_truth_attributes("mean", tile_name, settings, r.stats.spp, error);
    r.variance.attributes = reference::ground_truth_attributes("variance", tile_name, settings, r.stats.spp, error);
  }
  if (a.no_specular) image::write_exr(a.out, image::subtract_rgb(r.hdr, r.specular));
  else if (a.ext == ".exr") image::write_exr(a.out, r.hdr);
  else image::write_png(a.out, r.display);
  if (!a.variance.empty()) image::write_exr(a.variance, r.variance);
  if (!a.png.empty()) image::write_png(a.png, r.display);
  if (!a.summary.empty()) {
    nlohmann::json j = summary_common(argc, argv, pixel_settings(argc, argv), a.width, a.height, r.stats, used_threads);
    j.update({{"method", "diffusion"},
              {"estimator", "probe"},
              {"kernel", a.kernel},
              {"shadows", a.shadows},
              {"probes", r.stats.probes},
              {"hits", r.stats.hits},
              {"shadow_rays", r.stats.shadow_rays},
              {"seconds", r.stats.total_ms * 1e-3}});
    image::write_file_atomically(a.summary, j.dump(2) + "\n");
  }
  if (a.stats) print_stats(r.stats);
}

void render_walk(const Args& a, const scene::Scene& s, const Progress& progress, int argc, char** argv,
                 int used_threads) {
  reference::GroundTruthOptions o;
  o.width = std::uint32_t(a.width);
  o.height = std::uint32_t(a.height);
  o.spp = a.spp;
  o.target_error = a.target_error;
  o.diffuse_only = a.diffuse_only;
  o.exitance = a.exitance;
  o.threads = a.threads;
  o.seed = a.seed;
  o.exposure = a.exposure;
  o.tile = a.tile;
  o.on_warning = [](const std::string& w) { std::cerr << "sss-reference: warning: " << w << '\n'; };
  if (a.spp == 1)
    std::cerr << "sss-reference: warning: --spp 1: one sample per pixel says nothing of the noise; the "
                 "variance is written as 0 and the relative standard error is unknown (nan)\n";
  reference::GroundTruthImage r = reference::render_ground_truth(s, o, progress, &g_cancel);
  if (g_cancel.load()) throw reference::Cancelled();
  const std::string settings = pixel_settings(argc, argv);
  const std::string tile_name = a.tile.whole() ? "" : a.tile_text;
  const double error = r.stats.relative_standard_error;
  r.hdr.attributes = reference::ground_truth_attributes("mean", tile_name, settings, r.stats.spp, error);
  r.variance.attributes = reference::ground_truth_attributes("variance", tile_name, settings, r.stats.spp, error);
  if (a.ext == ".exr") image::write_exr(a.out, r.hdr);
  else image::write_png(a.out, r.display);
  if (!a.variance.empty()) image::write_exr(a.variance, r.variance);
  if (!a.png.empty()) image::write_png(a.png, r.display);
  if (!a.summary.empty()) {
    const reference::WalkStats& w = r.stats.walk;
    nlohmann::json j = summary_common(argc, argv, settings, a.width, a.height, r.stats, used_threads);
    j.update({{"paths", w.paths},
              {"scattering_events", w.scattering_events},
              {"boundary_reflections", w.boundary_hits},
              {"direct_beams", w.beams},
              {"escaped", w.escaped},
              {"truncated", w.truncated},
              {"setup_seconds", r.stats.setup_seconds},
              {"seconds", r.stats.seconds},
              {"warnings", r.stats.warnings}});
    image::write_file_atomically(a.summary, j.dump(2) + "\n");
  }
  if (a.stats) print_stats(r.stats, used_threads);
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
  Args a;
  add_options(app, a);
  if (const auto stop = parse_command_line(app, argc, argv, "sss-reference")) return *stop;
  if (const auto stop = check_modes(app, a)) return *stop;
  if (const auto stop = check_values(app, a)) return *stop;
  if (const auto stop = check_files(a)) return *stop;
  auto loaded = load_cli_scene("sss-reference", a.scene_name, a.material, a.environment, std::uint32_t(a.height));
  if (const int* stop = std::get_if<int>(&loaded)) return *stop;
  const scene::Scene& s = std::get<scene::Scene>(loaded);
  reference::ReferenceOptions diffusion = diffusion_options(a);
  if (a.choose_later)
    if (const auto stop = choose(a, s, diffusion)) return *stop;
  const int used_threads = a.threads > 0 ? a.threads : int(std::thread::hardware_concurrency());
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  ProgressBar bar(!a.quiet);
  auto progress = [&](const char* stage, double f) { bar(stage, f); };
  try {
    if (!a.walk)
      render_diffusion(a, s, diffusion, progress, argc, argv, used_threads);
    else
      render_walk(a, s, progress, argc, argv, used_threads);
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
