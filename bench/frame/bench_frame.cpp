// bench_frame: per-pass GPU times of the real-time renderer over many frames of one
// configuration, in one process (issue 5's frame-rate target: builtin:bunny, 960x540,
// screen separable SSS, >= 15 fps on 2 CPU cores with lavapipe). Prints, per pass, the
// minimum and the median over the measured frames (after --warmup frames that compile
// the pipelines' variants): on a shared machine the minimum is the figure to compare
// (contention only adds time), the median says how noisy the run was.
//   bench_frame [SCENE] [--width W] [--height H] [--frames N] [--warmup N]
//               [--sss off|screen|texture] [--mode separable|gaussians] [--taps N]
//               [--transmission on|off] [--single-scattering on|off] [--aa off|fxaa] [--look-away] [--texture-size N]
//               [--texture-update every-frame|on-change] [--objects N] [--environment R,G,B|FILE.exr] [--sky-occlusion on|off]
//               [--out FILE.png]
// --objects N: N copies of the scene's instances side by side along x (one bounding
// diameter apart), the camera moved back along its view to frame them all (issue 6: the
// texture path's cost against the screen path for one and for three SSS objects).
// It depends on the renderer library only (not on the viewer), so that it builds while
// the viewer is being worked on. bench/pass_times.sh runs it.
#include "renderer/Renderer.h"
#include "image/Image.h"
#include "scene/BuiltinScenes.h"
#include "scene/Environment.h"
#include "renderer/vk/Context.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

using namespace sss;

namespace {

int usage(const char* message) {
  std::fprintf(stderr,
               "bench_frame: %s\nusage: bench_frame [SCENE] [--width W] [--height H] "
               "[--frames N] [--warmup N] [--sss off|screen|texture] [--mode separable|gaussians] "
               "[--taps N] [--transmission on|off] [--single-scattering on|off] [--aa off|fxaa] [--look-away] [--texture-size N] "
               "[--texture-update every-frame|on-change] [--objects N] [--environment R,G,B|FILE.exr] "
               "[--sky-occlusion on|off]\n",
               message);
  return 2;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// CPU time of the whole process (every lavapipe thread), in ms: unlike the GPU timestamps
// (wall clock), it hardly grows when other processes share the cores.
double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_name = "builtin:bunny";
  renderer::RenderOptions options;
  options.width = 960;
  options.height = 540;
  std::string sss = "screen", mode = "separable";  // --sss, --mode
  int frames = 20;
  int warmup = 3;
  bool look_away = false;  // turn the camera around: an all-background frame (masking cost)
  int objects = 1;
  std::string out;  // --out FILE.png: the last frame, to see what was measured
  std::string environment;  // --environment: a sky (scene::load_environment), for its cost
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    const auto value = [&]() { return std::string(argv[++i]); };
    if (arg.rfind("--", 0) != 0) {
      scene_name = arg;
    } else if (arg == "--look-away") {
      look_away = true;
    } else if (!has_value) {
      return usage(("missing value for " + arg).c_str());
    } else if (arg == "--width") {
      options.width = static_cast<std::uint32_t>(std::atoi(value().c_str()));
    } else if (arg == "--height") {
      options.height = static_cast<std::uint32_t>(std::atoi(value().c_str()));
    } else if (arg == "--frames") {
      frames = std::max(1, std::atoi(value().c_str()));
    } else if (arg == "--warmup") {
      warmup = std::max(0, std::atoi(value().c_str()));
    } else if (arg == "--taps") {
      options.separable_taps = std::atoi(value().c_str());
    } else if (arg == "--sss") {
      sss = value();
    } else if (arg == "--texture-size") {
      const std::string v = value();
      const long long size = std::atoll(v.c_str());
      if (const std::string e = renderer::texture_size_error(size); !e.empty() || v.empty())
        return usage(("--texture-size: " + e).c_str());
      options.texture_size = static_cast<std::uint32_t>(size);
    } else if (arg == "--texture-update") {
      const auto update = renderer::parse_texture_update(value());
      if (!update) return usage("--texture-update: expected every-frame or on-change");
      options.texture_update = *update;
    } else if (arg == "--out") {
      out = value();
    } else if (arg == "--objects") {
      objects = std::atoi(value().c_str());
      if (objects < 1 || objects > 64) return usage("--objects: expected 1..64");
    } else if (arg == "--transmission") {
      const std::string v = value();
      if (v != "on" && v != "off") return usage("--transmission: expected on or off");
      options.transmission = v == "on";
    } else if (arg == "--single-scattering") {
      const std::string v = value();
      if (v != "on" && v != "off") return usage("--single-scattering: expected on or off");
      options.single_scattering = v == "on";
    } else if (arg == "--aa") {
      const auto aa = renderer::parse_antialias(value());
      if (!aa) return usage("--aa: expected off or fxaa");
      options.antialias = *aa;
    } else if (arg == "--sky-occlusion") {
      const std::string v = value();
      if (v != "on" && v != "off") return usage("--sky-occlusion: expected on or off");
      options.sky_occlusion = v == "on";
    } else if (arg == "--environment") {
      environment = value();
    } else if (arg == "--mode") {
      mode = value();
    } else {
      return usage(("unknown option " + arg).c_str());
    }
  }
  auto technique = renderer::technique_from_cli(sss, mode);
  if (auto* error = std::get_if<std::string>(&technique)) return usage(error->c_str());
  options.technique = std::get<renderer::SssTechnique>(technique);

  auto loaded = scene::load_scene(scene_name);
  if (auto* e = std::get_if<scene::LoadError>(&loaded)) return usage(e->what().c_str());
  scene::Scene scene = std::move(std::get<scene::Scene>(loaded));
  scene::add_camera_if_missing(scene);
  scene::add_light_if_missing(scene);
  if (!environment.empty()) {
    try {
      scene.environment = scene::load_environment(environment);
    } catch (const std::exception& e) {
      return usage(e.what());
    }
  }
  if (objects > 1) {
    const scene::Bounds one = scene.bounds();
    const float step = 2.0f * one.radius();
    const std::size_t n = scene.instances.size();
    for (int k = 1; k < objects; ++k)
      for (std::size_t i = 0; i < n; ++i) {
        scene::Instance copy = scene.instances[i];
        copy.world = glm::translate(glm::mat4(1.0f), glm::vec3(step * float(k), 0.0f, 0.0f)) * copy.world;
        copy.node += "#" + std::to_string(k + 1);
        scene.instances.push_back(copy);
      }
    // Back along the view until the camera's field of view holds all copies.
    scene::Camera& cam = scene.cameras.front();
    const glm::vec3 forward = -glm::vec3(cam.world[2]);
    const scene::Bounds all = scene.bounds();
    const glm::vec3 shift = all.center() - one.center();
    cam.world[3] += glm::vec4(shift - forward * (all.radius() - one.radius()) * 2.0f, 0.0f);
    cam.zfar *= float(objects) * 2.0f;
  }
  if (look_away) {
    glm::mat4& w = scene.cameras.front().world;
    w[2] = -w[2];  // view direction reversed (and x, to keep the basis right-handed)
    w[0] = -w[0];
  }

  try {
    vk::Context context;
    renderer::Renderer r(context, scene, options);
    for (int i = 0; i < warmup; ++i) r.render_frame();
    std::vector<std::string> order;
    std::map<std::string, std::vector<double>> ms;
    for (int i = 0; i < frames; ++i) {
      const double cpu_start = process_cpu_ms();
      r.render_frame();
      ms["process cpu"].push_back(process_cpu_ms() - cpu_start);
      for (const vk::PassTime& p : r.stats().passes) {
        if (!ms.count(p.name)) order.push_back(p.name);
        ms[p.name].push_back(p.ms);
      }
      ms["gpu total"].push_back(r.stats().gpu_ms);
      ms["cpu frame"].push_back(r.stats().cpu_ms);
    }
    if (!out.empty()) image::write_png(out, r.read_display());
    order.push_back("gpu total");
    order.push_back("cpu frame");
    order.push_back("process cpu");
    std::printf("%s x%d %ux%u, sss %s (texture %u, %s), %d taps, %d frames after %d "
                "warm-up, %s\n",
                scene_name.c_str(), objects, options.width, options.height,
                std::string(renderer::technique_name(options.technique)).c_str(), options.texture_size,
                std::string(renderer::texture_update_name(options.texture_update)).c_str(),
                options.separable_taps, frames, warmup,
                std::getenv("LP_NUM_THREADS") ? "LP_NUM_THREADS set" : "default threads");
    std::printf("%-16s %10s %10s\n", "pass", "min ms", "median ms");
    for (const std::string& name : order) {
      const std::vector<double>& v = ms[name];
      std::printf("%-16s %10.2f %10.2f\n", name.c_str(), *std::min_element(v.begin(), v.end()),
                  median(v));
    }
    const double best = *std::min_element(ms["gpu total"].begin(), ms["gpu total"].end());
    std::printf("%-16s %10.1f %10.1f\n", "fps (gpu total)", 1000.0 / best,
                1000.0 / median(ms["gpu total"]));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_frame: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
