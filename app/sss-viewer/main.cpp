// sss-viewer: renders a scene with the real-time renderer, in a window (Window.h) or
// headless:
//   sss-viewer [SCENE] [--screenshot FILE --frames N] [--vsync on|off] [options]
//   sss-viewer [SCENE] --headless --out FILE.png|FILE.exr [options]
// The command-line contract is DESIGN.md §4; errors exit 2 (usage, input) or 1 (runtime).
#include "SceneArgs.h"
#include "CliSupport.h"
#include "FrameOutput.h"
#include "InputFiles.h"
#include "Soak.h"
#include "ViewerArgs.h"
#include "Ui.h"
#include "Window.h"

#include "renderer/Renderer.h"
#include "renderer/SssTexturePass.h"
#include "image/AtomicFile.h"
#include "image/Image.h"
#include "scene/BuiltinScenes.h"
#include "renderer/vk/Context.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <iostream>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <new>

using namespace sss;
using namespace sss::app;

namespace {

int usage(const std::string& message) { return usage_error("sss-viewer", message); }

std::string debug_view_names() {
  std::string names;
  for (renderer::DebugView v : renderer::all_debug_views())
    names += (names.empty() ? "" : " | ") + std::string(renderer::debug_view_name(v));
  return names;
}

std::string debug_view_help() {
  return "The PNG / window shows an intermediate instead of the shaded frame (the EXR stays "
         "shaded): " + debug_view_names() + " (default none). irradiance: E/pi, specular, "
         "scattered: diffuse after SSS before albedo (/pi), all tonemapped; kernel-radius: "
         "viridis on log2 pixels, 1 px (dark blue) .. the largest radius on screen "
         "(yellow), magenta below 1 px (the screen kernel undersamples the profile); "
         "profile-id: one colour per material; thickness: mm through the object along light "
         "0, viridis 0 .. the largest SSS object's bounding diameter; uv-stretch: red = mm "
         "per unit u, green = mm per unit v, 0 .. pi x that diameter, grey without UVs; "
         "single-scattering: S(1) alone (tonemapped), whether --single-scattering is on or "
         "off. --debug-range sets the heat maps' ends; the headless viewer prints the range it "
         "drew with";
}

void write_atlases(const renderer::Renderer& r, const std::string& prefix,
                   const std::vector<std::filesystem::path>& inputs) {
  using Atlas = renderer::Renderer::Atlas;
  const auto& objects = r.texture_pass()->objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    for (const auto& [which, name] : {std::pair{Atlas::Irradiance, "irradiance"},
                                      std::pair{Atlas::Scattered, "scattered"},
                                      std::pair{Atlas::Stretch, "stretch"}}) {
      // The object's index keeps two objects of one name (a node's primitives) apart.
      const std::string path = prefix + "-" + std::to_string(i) + "-" + objects[i].options.name +
                               "-" + name + ".exr";
      if (auto refused = refuse_input_overwrite(path, inputs))
        throw std::runtime_error("--atlas-out: " + *refused);
      image::write_exr(path, r.read_atlas(i, which));
      std::printf("wrote %s\n", path.c_str());
    }
  }
}

void print_stats(const renderer::Renderer& r, int frames, double cpu_total_ms) {
  const renderer::FrameStats& s = r.stats();
  std::printf("frame %ux%u, sss %s, %d frame(s)\n", r.options().width,
              r.options().height, std::string(renderer::technique_name(r.options().technique)).c_str(), frames);
  print_pass_times(s);
  std::printf("%-16s %10.3f\n", "cpu mean", cpu_total_ms / frames);
  print_target_memory(r);
  if (r.sky_bake_seconds() > 0.0)
    std::printf("%-16s %10.3f s (the per-vertex bake, once per scene and atlas)\n", "sky occlusion",
                r.sky_bake_seconds());
}

// The scene and how it is drawn.
// The scene, the output, the frame's size and the technique, materials and lights.
void add_frame_options(CLI::App& app, ViewerArgs& a) {
  app.add_option("scene", a.scene, "A glTF/GLB file or builtin:NAME (default builtin:bunny)");
  app.add_flag("--headless", a.headless, "Render without a window and write --out");
  app.add_option("--out", a.out, "Output image: FILE.png (tonemapped) or FILE.exr (linear)");
  app.add_option("--screenshot", a.screenshot, "Window mode: save after --frames and exit");
  app.add_option("--width", a.width, "Image width (default 640)")->check(CLI::Range(1, 16384));
  app.add_option("--height", a.height, "Image height (default 360)")->check(CLI::Range(1, 16384));
  app.add_option("--frames", a.frames, "Frames to render (default 1)")->check(CLI::Range(1, 100000));
  app.add_option("--sss", a.sss, "off | screen | texture (default screen)");
  app.add_option("--mode", a.mode, "separable | gaussians (default separable)");
  add_material_override_options(app, a.material);
  add_environment_options(app, a.environment);
  app.add_option("--taps", a.taps, "Separable kernel taps (odd, 3..33; default 17)");
  app.add_option("--shadow-map-size", a.shadow_map_size,
                 "Shadow map texels a side, per light (16..8192; default 1024). The golden suite "
                 "renders at 512 (tests/golden/REPORT.md)")
      ->check(CLI::Range(16, 8192));
}

// How the image is shown: exposure, anti-aliasing, background, the debug views.
void add_image_options(CLI::App& app, ViewerArgs& a) {
  app.add_option("--exposure", a.exposure, "Exposure of the PNG (default 1, in [1e-6, 1e6])");
  app.add_option("--aa", a.aa,
                 "auto | off | fxaa: anti-aliasing of the displayed frame and the PNG, FXAA over "
                 "the tonemapped image (the EXR is never filtered). auto (default): fxaa in the "
                 "window, off headless, where the PNG is the frame the golden suite compares");
  app.add_option("--background", a.background,
                 "auto | none | environment | R,G,B: what is behind the geometry in the displayed "
                 "frame and the PNG (the EXR keeps 0 there). R,G,B: a colour, sRGB in [0, 1], "
                 "opaque. environment: the --environment light as the camera sees it, opaque. "
                 "none: black, and the PNG is transparent there. auto (default): in the window "
                 "the environment when there is one, else a dark grey; none headless");
  app.add_option("--debug-view", a.debug_view, debug_view_help());
  app.add_option("--debug-range", a.debug_range,
                 "LO,HI: the debug view's heat map from LO to HI in its unit (kernel-radius: "
                 "pixels, LO > 0; thickness: mm; uv-stretch: mm per unit of UV). Default: the "
                 "view's automatic range")
      ->delimiter(',')
      ->expected(2);
}

// The subsurface terms (transmission, Fresnel, single scattering), texture space's
// settings, and the scattered light alone.
void add_sss_term_options(CLI::App& app, ViewerArgs& a) {
  app.add_option("--transmission", a.transmission,
                 "on | off: light through thin parts of SSS materials, thickness from the "
                 "shadow maps (default on)");
  app.add_option("--sky-occlusion", a.sky_occlusion,
                 "on | off: with --environment, take away the sky the scene blocks (its "
                 "spherical-harmonic transfer, ray-cast per vertex of each object when first "
                 "needed; default on). Off: every surface sees the whole sky");
  app.add_option("--fresnel", a.fresnel,
                 "on | off: directional Fresnel factors on subsurface light, F_t(eta, theta_i) "
                 "entering and F_t(eta, theta_o)/(c pi) leaving instead of Lambert's 1/pi "
                 "(default off: closer to the ground truth away from silhouettes, with single scattering or without, "
                 "README \"Directional Fresnel\")");
  app.add_option("--single-scattering", a.single_scattering,
                 "on | off: once-scattered light S(1) per pixel (planar closed form, the "
                 "material's real g, shadowed, not blurred) with profiles that leave their own "
                 "out (default on: closer to the ground truth; README \"Single scattering\")");
  app.add_option("--texture-size", a.texture_size,
                 "--sss texture: each object's irradiance texture size, 256..2048 (default 1024)");
  app.add_option("--texture-update", a.texture_update,
                 "--sss texture: every-frame | on-change (default; recompute an object's "
                 "irradiance only when lights, materials or its size change)");
  app.add_option("--texture-object", a.texture_objects,
                 "--sss texture: NAME=SIZE[:every-frame|on-change] for one object (the scene "
                 "node's name); repeatable");
  app.add_option("--atlas-out", a.atlas_out,
                 "Headless --sss texture: also write each object's atlases as linear EXR, "
                 "PREFIX-I-NAME-irradiance.exr (E), -scattered.exr (sum of w_i E*G_i) and "
                 "-stretch.exr (mm per texel along u, v); alpha is the UV island + 1");
  app.add_flag("--no-specular", a.no_specular,
               "Headless, EXR --out: write the frame less its specular, the light that scattered (with its "
               "albedo) and the opaque diffuse; compare with sss-reference --no-specular (the error budget's "
               "scattered light)");
}

// Every option of the frame, in --help's order.
void add_render_options(CLI::App& app, ViewerArgs& a) {
  add_frame_options(app, a);
  add_image_options(app, a);
  add_sss_term_options(app, a);
}

// How the viewer runs: statistics, the device, the window, the soak, and the tests' hooks.
void add_run_options(CLI::App& app, ViewerArgs& a) {
  app.add_flag("--stats", a.stats, "Print GPU time per pass and the CPU frame time");
  app.add_flag("--describe-frame", a.describe_frame,
               "Print the frame's passes in order, each step with the images it reads and writes "
               "(the frame graph, for these options and scene), and exit without rendering");
  app.add_option("--device", a.device, "Vulkan device (case-insensitive substring of its name)");
  app.add_option("--vsync", a.vsync, "Window: on (FIFO, default) | off (MAILBOX or IMMEDIATE)");
  app.add_flag("--validation", a.validation,
               "Load the Vulkan validation layer with synchronization checks (also SSS_VALIDATION=1)");
  app.add_option("--interactive-scale", a.interactive_scale,
                 "Window: render size, as a fraction of the window, while the view moves or a "
                 "slider is dragged (default 0.5; 1 = always full size)")
      ->check(CLI::Range(0.1f, 1.0f));
  app.add_flag("--test-resize", a.test_resize)->group("");
  // tests: 50 window size changes over ~17 frames (1x1, larger than the screen, thin; two
  // before a frame's size is read and one between rendering and acquiring), then back
  // to --width x --height; --screenshot counts --frames from there
  app.add_flag("--test-resize-storm", a.test_resize_storm)->group("");
  // tests: std::bad_alloc (host memory exhausted) after loading the scene ("load") or in
  // the frame loop ("frame": the window's frame 2, after the first headless frame)
  app.add_option("--test-host-oom", a.test_host_oom)->group("")->check(CLI::IsMember({"load", "frame"}));
  app.add_flag("--test-interaction", a.test_interaction)->group("");  // timing: always scaled  // tests: resize/minimize the window
  // tests and timing: one material edit through the panel's code path at the first frame;
  // --screenshot then waits for its refit to be presented (--stats prints its latency)
  app.add_option("--test-edit", a.test_edit)->group("");
  app.add_option("--test-open", a.test_open)->group("");  // tests: open a file, as a drop does
  // tests: the Compare button at frame 2, then split | reference | error | log-ratio is shown;
  // --screenshot waits for the comparison (--stats prints its metrics)
  app.add_option("--test-compare", a.test_compare)->group("");
  app.add_option("--soak", a.soak,
                 "Headless soak: render N frames, changing the first SSS material every "
                 "--soak-every frames through the material panel's code; record resident "
                 "memory after every frame and live Vulkan objects; exit 1 if memory grows "
                 "significantly by --soak-max-growth-kb or more after the first material cycle, "
                 "or an object leaks (scripts/soak.sh)")
      ->check(CLI::Range(1, 10000000));
  app.add_option("--soak-every", a.soak_every, "--soak: frames between material changes (default 100)")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--soak-cycle", a.soak_cycle,
                 "--soak: steps in the material cycle: the accepted presets in order, the last "
                 "step a coefficient edit (default 10); warm-up is one cycle")
      ->check(CLI::Range(1, 1000));
  app.add_option("--soak-max-growth-kb", a.soak_max_growth_kb,
                 "--soak: allowed RSS growth over the cycles after warm-up (default 1024)")
      ->check(CLI::Range(0L, 1L << 30));
  app.add_option("--soak-csv", a.soak_csv, "--soak: write frame,rss_kb,rss_median_kb,vk_objects,heap_kb,material here");
  app.add_option("--soak-svg", a.soak_svg, "--soak: plot resident memory and objects here (SVG)");
}

// Which outputs go with which run (window, headless, soak) and the tests' scripts; an
// exit status where they do not fit.
std::optional<int> check_outputs(const ViewerArgs& a) {
  const bool soak_options = a.soak > 0 || !a.soak_csv.empty() || !a.soak_svg.empty();
  if (soak_options && (!a.headless || a.soak == 0))
    return usage("--soak-csv and --soak-svg need --soak N, and --soak needs --headless");
  if (a.headless && !a.describe_frame) {
    if (a.out.empty() && a.soak == 0) return usage("--headless needs --out FILE.png|FILE.exr");
    const std::string ext = lower_extension(a.out);
    if (!a.out.empty() && ext != ".png" && ext != ".exr")
      return usage("--out: expected a .png or .exr file name, got '" + a.out + "'");
    if (a.no_specular && ext != ".exr")
      return usage("--no-specular: writes linear values, --out must be a .exr file, got '" + a.out + "'");
  } else {
    if (a.no_specular) return usage("--no-specular needs --headless and --out FILE.exr");
    if (!a.out.empty())
      return usage("--out needs --headless (the window saves with --screenshot FILE)");
    const std::string shot = lower_extension(a.screenshot);
    if (!a.screenshot.empty() && shot != ".png" && shot != ".exr")
      return usage("--screenshot: expected a .png or .exr file name, got '" + a.screenshot + "'");
  }
  if (!a.test_compare.empty() && a.test_compare != "split" && a.test_compare != "reference" &&
      a.test_compare != "error" && a.test_compare != "log-ratio")
    return usage("--test-compare: expected split, reference, error or log-ratio");
  if (!a.test_edit.empty() && !valid_script_edit(a.test_edit))
    return usage("--test-edit: expected preset=NAME, model=NAME or layers=FILE.json, got '" +
                 a.test_edit + "'");
  if (a.vsync != "on" && a.vsync != "off")
    return usage("--vsync: expected on or off, got '" + a.vsync + "'");
  return std::nullopt;
}

// --sss, --mode and what each mode takes, into `options`; an exit status where bad.
std::optional<int> set_sss_options(const ViewerArgs& a, renderer::RenderOptions& options) {
  auto technique = renderer::technique_from_cli(a.sss, a.mode);
  if (auto* error = std::get_if<std::string>(&technique)) return usage(*error);
  options.technique = std::get<renderer::SssTechnique>(technique);
  if (const std::string e = renderer::texture_size_error(a.texture_size); !e.empty())
    return usage("--texture-size: " + e);
  options.texture_size = static_cast<std::uint32_t>(a.texture_size);
  const auto update = renderer::parse_texture_update(a.texture_update);
  if (!update)
    return usage("--texture-update: expected every-frame or on-change, got '" + a.texture_update + "'");
  options.texture_update = *update;
  if (!a.atlas_out.empty() && (!a.headless || options.technique != renderer::SssTechnique::Texture))
    return usage("--atlas-out needs --sss texture and --headless");
  for (const std::string& t : a.texture_objects) {
    auto object = renderer::parse_texture_object(t, options.texture_update);
    if (auto* error = std::get_if<std::string>(&object)) return usage("--texture-object: " + *error);
    options.texture_objects.push_back(std::get<renderer::TextureObjectOptions>(std::move(object)));
  }
  if (a.taps < 3 || a.taps > 33 || a.taps % 2 == 0)
    return usage("--taps: expected an odd number in 3..33, got " + std::to_string(a.taps));
  options.separable_taps = a.taps;
  options.shadow_map_size = std::uint32_t(a.shadow_map_size);
  return std::nullopt;
}

// The frame: its size and exposure, anti-aliasing, background, debug view and the
// lighting switches, into `options`; an exit status where bad.
// The on | off options, each one RenderOptions flag.
std::optional<int> set_switches(const ViewerArgs& a, renderer::RenderOptions& o) {
  const struct {
    const char* flag;
    const std::string& value;
    bool& out;
  } switches[] = {{"--transmission", a.transmission, o.transmission},
                  {"--sky-occlusion", a.sky_occlusion, o.sky_occlusion},
                  {"--fresnel", a.fresnel, o.fresnel},
                  {"--single-scattering", a.single_scattering, o.single_scattering}};
  for (const auto& s : switches) {
    if (s.value != "on" && s.value != "off")
      return usage(std::string(s.flag) + ": expected on or off, got '" + s.value + "'");
    s.out = s.value == "on";
  }
  return std::nullopt;
}

std::optional<int> set_frame_options(const ViewerArgs& a, renderer::RenderOptions& options) {
  if (!(a.exposure >= 1e-6 && a.exposure <= 1e6))  // also NaN (CLI::Range would let it through)
    return usage("--exposure: must lie in [1e-06, 1e+06], got " + std::to_string(a.exposure));
  if (std::size_t(a.width) * std::size_t(a.height) > image::kMaxImagePixels)
    return usage("--width x --height: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                 " is more than " + std::to_string(image::kMaxImagePixels) + " pixels");
  options.width = static_cast<std::uint32_t>(a.width);
  options.height = static_cast<std::uint32_t>(a.height);
  options.exposure = a.exposure;
  if (a.aa == "auto") {
    options.antialias = a.headless ? renderer::Antialias::Off : renderer::Antialias::Fxaa;
  } else if (const auto aa = renderer::parse_antialias(a.aa)) {
    options.antialias = *aa;
  } else {
    return usage("--aa: expected auto, off or fxaa, got '" + a.aa + "'");
  }
  if (a.background == "auto") {
    if (!a.headless) {
      options.background = kWindowBackground;  // where there is no environment
      options.background_environment = true;
    }
  } else if (a.background == "environment") {
    if (a.environment.environment == "none")
      return usage("--background environment: no environment to show; give one with "
                   "--environment R,G,B|FILE.exr");
    options.background_environment = true;
  } else if (a.background != "none") {
    auto rgb = parse_rgb("--background", a.background);
    if (auto* e = std::get_if<FieldError>(&rgb)) return usage(e->what());
    const Rgb& c = std::get<Rgb>(rgb);
    options.background = std::array<float, 3>{float(c[0]), float(c[1]), float(c[2])};
    if (const std::string e = renderer::background_error(*options.background); !e.empty())
      return usage("--background: " + e);
  }
  const auto debug_view = renderer::parse_debug_view(a.debug_view);
  if (!debug_view)
    return usage("--debug-view: expected " + debug_view_names() + ", got '" + a.debug_view + "'");
  options.debug_view = *debug_view;
  if (!a.debug_range.empty()) {
    if (!renderer::debug_view_has_range(options.debug_view))
      return usage("--debug-range: the debug view '" + a.debug_view + "' has no heat map "
                   "(kernel-radius, thickness and uv-stretch have)");
    options.debug_range = {float(a.debug_range[0]), float(a.debug_range[1])};
    if (const std::string e = renderer::debug_range_error(options.debug_view, options.debug_range);
        !e.empty())
      return usage("--debug-range: " + e);
  }
  return set_switches(a, options);
}

// Renders --frames headless and writes --out (and --atlas-out), printing the debug
// view's range and --stats.
void run_headless(const ViewerArgs& a, const scene::Scene& scene, const renderer::RenderOptions& options,
                  const std::vector<std::filesystem::path>& inputs) {
  vk::Context context(headless_context_options(a));
  renderer::Renderer r(context, scene, options);
  print_warnings(r);
  double cpu_total = 0.0;
  for (int i = 0; i < a.frames; ++i) {
    r.render_frame();
    cpu_total += r.stats().cpu_ms;
    if (a.test_host_oom == "frame") throw std::bad_alloc();
  }
  if (a.no_specular)
    image::write_exr(a.out, frame_less_specular(r));
  else
    write_frame(r, a.out);
  if (!a.atlas_out.empty()) write_atlases(r, a.atlas_out, inputs);
  if (renderer::debug_view_has_range(options.debug_view)) {  // the PNG's scale
    const auto [lo, hi] = r.debug_range();
    std::cout << "debug view " << a.debug_view << ": heat map " << lo << " .. " << hi << ' '
              << renderer::debug_view_unit(options.debug_view)
              << (a.debug_range.empty() ? " (automatic; --debug-range sets it)\n" : "\n");
  }
  if (a.stats) print_stats(r, a.frames, cpu_total);
}

int viewer_main(int argc, char** argv) {
  CLI::App app{"sss-viewer: real-time subsurface scattering (Vulkan), in a window or headless.",
               "sss-viewer"};
  ViewerArgs a;
  add_render_options(app, a);
  add_run_options(app, a);
  if (const auto stop = parse_command_line(app, argc, argv, "sss-viewer")) return *stop;

  if (const char* v = std::getenv("SSS_VALIDATION"); v != nullptr && std::string(v) == "1")
    a.validation = true;
  if (const auto stop = check_outputs(a)) return *stop;
  renderer::RenderOptions options;
  if (const auto stop = set_sss_options(a, options)) return *stop;
  if (const auto stop = set_frame_options(a, options)) return *stop;
  auto loaded = load_cli_scene("sss-viewer", a.scene, a.material, a.environment, std::uint32_t(a.height));
  if (const int* stop = std::get_if<int>(&loaded)) return *stop;
  scene::Scene scene = std::move(std::get<scene::Scene>(loaded));
  if (a.test_host_oom == "load") throw std::bad_alloc();
  // No output may replace a file the scene was loaded from (checked again where a file
  // is written after another scene was opened).
  const std::vector<std::filesystem::path> inputs = scene_input_files(a.scene);
  for (const auto& [option, path] : {std::pair{"--out", &a.out}, std::pair{"--screenshot", &a.screenshot},
                                     std::pair{"--soak-csv", &a.soak_csv},
                                     std::pair{"--soak-svg", &a.soak_svg}})
    if (auto refused = refuse_input_overwrite(*path, inputs))
      return usage(std::string(option) + ": " + *refused);

  try {
    if (a.describe_frame) {
      vk::Context context(headless_context_options(a));
      std::cout << renderer::Renderer(context, scene, options).describe_frame();
      return kExitOk;
    }
    if (!a.headless) return run_window(a, scene, options);
    if (a.soak > 0) return run_soak(a, scene, options);
    run_headless(a, scene, options, inputs);
  } catch (const std::bad_alloc&) {
    std::cerr << "sss-viewer: error: out of host memory (std::bad_alloc)\n";
    return kExitRuntime;
  } catch (const std::invalid_argument& e) {
    return usage(e.what());
  } catch (const std::exception& e) {
    // A --device that names no device is bad input, not a runtime failure.
    if (!a.device.empty() && std::string(e.what()).find("no Vulkan device matches") != std::string::npos)
      return usage(e.what());
    std::cerr << "sss-viewer: error: " << e.what() << '\n';
    return kExitRuntime;
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // A fixed mmap threshold: blocks of 128 KiB and more (frame readbacks, decoded images,
  // upload staging) are mapped and unmapped, never carved from the heap. glibc's default
  // raises the threshold after each such free (up to 32 MiB), after which these blocks
  // come from the heap and a later one can land past the top and stay resident: the
  // 10,000-frame soak grew 1.1 MB that way while the live heap grew 13 kB.
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif
  // Whatever escapes (host memory exhausted while loading, parsing or building the
  // window's state) is a runtime failure with a message, never an abort: exit 1.
  try {
    return viewer_main(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "sss-viewer: error: out of host memory (std::bad_alloc)\n";
  } catch (const std::exception& e) {
    std::cerr << "sss-viewer: error: " << e.what() << '\n';
  }
  return kExitRuntime;
}
