// sss-reference: the offline CPU reference renderer (DESIGN.md §4, §6).
//   sss-reference SCENE --out FILE.exr [--width W] [--height H] [--model M] [MEDIUM] ...
// Errors exit 2 (usage, input) or 1 (runtime); Ctrl-C (SIGTERM) stops the render, writes
// nothing and exits 130 (143).
#include "CliSupport.h"
#include "MaterialOverrides.h"

#include "renderer/image/AtomicFile.h"
#include "renderer/image/Image.h"
#include "renderer/reference/ReferenceRenderer.h"
#include "renderer/scene/BuiltinScenes.h"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

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

// A one-line bar redrawn in place on a terminal; on a pipe or file, one line per stage.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), tty_(isatty(STDERR_FILENO) == 1) {}
  void operator()(const char* stage, double fraction) {
    if (!enabled_) return;
    const std::string name(stage);
    const int percent = int(std::clamp(fraction, 0.0, 1.0) * 100.0);
    if (tty_) {
      if (name == stage_ && percent == percent_) return;
      const int width = 30, filled = percent * width / 100;
      std::fprintf(stderr, "\r%-10s [%s%s] %3d%%", stage, std::string(std::size_t(filled), '#').c_str(),
                   std::string(std::size_t(width - filled), '.').c_str(), percent);
      if (percent == 100) std::fputc('\n', stderr);
      std::fflush(stderr);
    } else if (percent == 100 && name != stage_done_) {
      std::fprintf(stderr, "sss-reference: %s done\n", stage);
      stage_done_ = name;
    }
    stage_ = name;
    percent_ = percent;
  }

 private:
  bool enabled_, tty_;
  std::string stage_, stage_done_;
  int percent_ = -1;
};

void print_stats(const reference::ReferenceStats& s) {
  std::fprintf(stderr, "sss-reference: %zu irradiance points\n", s.points);
  for (const reference::GroupStats& g : s.groups)
    std::fprintf(stderr, "  %-24s %9zu points, spacing %.3f mm, area %.1f mm^2, %zu octree nodes\n",
                 g.material.c_str(), g.points, g.spacing_mm, g.area_mm2, g.octree.nodes);
  std::fprintf(stderr,
               "  time: profiles %.0f ms, points %.0f ms, irradiance %.0f ms, octree %.0f ms, "
               "render %.0f ms, total %.0f ms\n",
               s.profile_ms, s.sampling_ms, s.irradiance_ms, s.octree_ms, s.render_ms, s.total_ms);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "sss-reference: offline CPU reference for subsurface scattering (Jensen & Buhler 2002): "
      "irradiance points, an octree, and the exact diffusion profile (no Gaussian fit)",
      "sss-reference"};
  std::string scene_name = std::string(scene::kDefaultScene);
  std::string out, png;
  int width = 640, height = 360, threads = 0;
  double spacing = 0.5, error_bound = 0.3;
  std::size_t max_points = 8'000'000;
  std::uint64_t seed = 1;
  float exposure = 1.0f;
  bool brute = false, diffuse_only = false, quiet = false, stats = false;
  MaterialOverrideArgs material;
  app.add_option("scene", scene_name, "A glTF/GLB file or builtin:NAME (default builtin:bunny)");
  app.add_option("--out", out, "Output: FILE.exr (linear radiance) or FILE.png (tonemapped)")->required();
  app.add_option("--png", png, "Also write the tonemapped image to this PNG");
  app.add_option("--width", width, "Image width (default 640)")->check(CLI::Range(1, 16384));
  app.add_option("--height", height, "Image height (default 360)")->check(CLI::Range(1, 16384));
  add_material_override_options(app, material);
  app.add_option("--spacing", spacing,
                 "Irradiance point spacing in reduced mean free paths (default 0.5; lower it for "
                 "more points and a more accurate sum)");
  app.add_option("--max-points", max_points, "Refuse to spread more points than this (default 8000000)");
  app.add_option("--error-bound", error_bound,
                 "Jensen-Buhler maximum solid angle (sr) of an octree node used whole (default 0.3; "
                 "0 descends to every point)");
  app.add_flag("--brute-force", brute, "Sum every irradiance point at every pixel (no octree)");
  app.add_flag("--diffuse-only", diffuse_only,
               "Write only the scattered diffuse term M/pi (no albedo, no specular, opaque surfaces black)");
  app.add_option("--threads", threads, "Worker threads (default 0: all cores)")->check(CLI::Range(0, 1024));
  app.add_option("--seed", seed, "Seed of the point sets (default 1)");
  app.add_option("--exposure", exposure, "Exposure of the PNG (default 1)");
  app.add_flag("--quiet", quiet, "No progress bar");
  app.add_flag("--stats", stats, "Print point counts and stage times on stderr");
  // CLI11 wraps "-1" to 2^64 - 1 for an unsigned option.
  app.get_option("--seed")->check(CLI::Validator(
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
  if (!(std::isfinite(spacing) && spacing > 0.0))
    return usage("--spacing: expected a finite number > 0 (mean free paths), got " + message_number(spacing));
  if (max_points == 0) return usage("--max-points: expected a number >= 1, got 0");
  if (!(std::isfinite(error_bound) && error_bound >= 0.0))
    return usage("--error-bound: expected a finite number >= 0 (sr), got " + message_number(error_bound));
  if (!(std::isfinite(exposure) && exposure > 0.0f))
    return usage("--exposure: expected a finite number > 0, got " + message_number(exposure));
  const std::string ext = lower_extension(out);
  if (ext != ".exr" && ext != ".png") return usage("--out: expected a .exr or .png file name, got '" + out + "'");
  if (!png.empty() && lower_extension(png) != ".png") return usage("--png: expected a .png file name, got '" + png + "'");

  // An output folder that is not there fails now rather than after a long render (the
  // write itself still reports every other failure).
  for (const std::string* file : {&out, &png}) {
    if (file->empty()) continue;
    const std::filesystem::path parent = std::filesystem::path(*file).parent_path();
    std::error_code ec;
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
      std::cerr << "sss-reference: error: " << *file << ": the folder " << parent.string()
                << " does not exist or is not a folder\n";
      return kExitRuntime;
    }
  }

  auto loaded = scene::load_scene(scene_name);
  if (auto* e = std::get_if<scene::LoadError>(&loaded)) return usage(e->what());
  scene::Scene s = std::move(std::get<scene::Scene>(loaded));
  scene::add_camera_if_missing(s);
  scene::add_light_if_missing(s);
  auto overridden = apply_material_overrides(s, material);
  if (auto* e = std::get_if<FieldError>(&overridden)) return usage(e->what());
  for (const std::string& w : s.warnings) std::cerr << "sss-reference: warning: " << w << '\n';

  reference::ReferenceOptions o;
  o.width = std::uint32_t(width);
  o.height = std::uint32_t(height);
  o.spacing_mfp = spacing;
  o.max_points = max_points;
  o.max_solid_angle = error_bound;
  o.brute_force = brute;
  o.diffuse_only = diffuse_only;
  o.threads = threads;
  o.seed = seed;
  o.exposure = exposure;

  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  ProgressBar bar(!quiet);
  try {
    const reference::ReferenceImage r = reference::render_reference(
        s, o, [&](const char* stage, double f) { bar(stage, f); }, &g_cancel);
    if (g_cancel.load()) throw reference::Cancelled();
    if (ext == ".exr")
      image::write_exr(out, r.hdr);
    else
      image::write_png(out, r.display);
    if (!png.empty()) image::write_png(png, r.display);
    if (stats) print_stats(r.stats);
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
