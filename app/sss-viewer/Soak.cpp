#include "Soak.h"

#include "CliSupport.h"
#include "FrameOutput.h"
#include "MaterialEditor.h"

#include "profiles/Presets.h"
#include "renderer/Renderer.h"
#include "image/AtomicFile.h"
#include "scene/Material.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Handle.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <malloc.h>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

namespace sss::app {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// The presets the material panel accepts (spectralon has no absorption and is refused,
// as in a glTF), with the edited material's model and settings.
std::vector<int> accepted_presets(const MaterialEdit& e) {
  std::vector<int> out;
  const auto all = profiles::presets();
  for (std::size_t i = 0; i < all.size(); ++i) {
    auto made = scene::make_sss_material(scene::PresetSource{std::string(all[i].name)},
                                         MaterialEditor::models()[std::size_t(e.model)],
                                         e.gaussians, e.scale,
                                         e.albedo == 1 ? scene::AlbedoMode::PrePost
                                                       : scene::AlbedoMode::PostScatter);
    if (std::holds_alternative<scene::SssMaterial>(made)) out.push_back(int(i));
  }
  return out;
}

// Linear axis ticks: a 1, 2 or 5 x 10^k step giving at most ~8 ticks over [lo, hi].
double tick_step(double lo, double hi) {
  const double span = std::max(hi - lo, 1e-9);
  const double base = std::pow(10.0, std::floor(std::log10(span / 8.0)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (span / (m * base) <= 8.0) return m * base;
  return 10.0 * base;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

long heap_kb() {
  // glibc's mallinfo2 (2.33+) sums every arena: uordblks in use, hblkhd mmapped chunks.
  const struct mallinfo2 m = mallinfo2();
  return static_cast<long>((m.uordblks + m.hblkhd) / 1024);
}

long resident_kb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmRSS:", 0) == 0) {  // "VmRSS:	  123456 kB" (proc(5))
      try {
        return std::stol(line.substr(6));
      } catch (const std::exception&) {
        return -1;
      }
    }
  }
  return -1;
}

namespace {

// The resident set's growth per cycle after warm-up: the peaks of each cycle, (warm-up +
// k period, warm-up + (k + 1) period] (the last may be partial), and the lower median of
// their rises times the number of rises, into v.rss_growth_kb. Returns whether every
// cycle was measured.
bool judge_rss(const std::vector<SoakSample>& samples, int period, SoakVerdict& v) {
  std::vector<long> peaks;
  for (const SoakSample& s : samples) {
    if (s.frame <= v.warmup_frames) continue;
    const std::size_t k = std::size_t((s.frame - v.warmup_frames - 1) / period);
    if (peaks.size() <= k) peaks.resize(k + 1, -1);
    peaks[k] = std::max(peaks[k], s.rss_kb);
  }
  const bool measured = std::all_of(peaks.begin(), peaks.end(), [](long p) { return p > 0; });
  if (peaks.size() == 1) {
    v.rss_growth_kb = 0;  // one cycle: nothing to compare, the objects decide
    return measured;
  }
  std::vector<long> rises;
  for (std::size_t k = 1; k < peaks.size(); ++k) rises.push_back(peaks[k] - peaks[k - 1]);
  // The lower median: the smallest of two rises, the 3rd smallest of six.
  const std::size_t m = (rises.size() - 1) / 2;
  std::nth_element(rises.begin(), rises.begin() + std::ptrdiff_t(m), rises.end());
  v.rss_growth_kb = rises[m] * long(rises.size());
  return measured;
}

// The same point of every cycle after warm-up holds the same number of live Vulkan
// objects; the first frame where it does not is named.
void judge_objects(const std::vector<SoakSample>& samples, int period, SoakVerdict& v) {
  std::map<int, std::int64_t> first;  // cycle phase -> count in the first cycle after warm-up
  v.objects_ok = true;
  for (const SoakSample& s : samples) {
    if (s.frame < v.warmup_frames) continue;
    const int phase = (s.frame - v.warmup_frames) % period;
    auto [it, inserted] = first.emplace(phase, s.vk_objects);
    if (!inserted && it->second != s.vk_objects && v.objects_ok) {
      v.objects_ok = false;
      v.objects_detail = "frame " + std::to_string(s.frame) + ": " +
                         std::to_string(s.vk_objects) + " live Vulkan objects, " +
                         std::to_string(it->second) + " at frame " +
                         std::to_string(s.frame - period * ((s.frame - v.warmup_frames) / period)) +
                         " (the same point of the material cycle)";
    }
  }
  if (v.objects_ok) {
    std::ostringstream d;
    d << "the same at each point of every cycle after warm-up:";
    for (const auto& [phase, count] : first) d << " +" << phase << ": " << count << ";";
    v.objects_detail = d.str();
  }
}

}  // namespace

SoakVerdict judge_soak(const std::vector<SoakSample>& samples, int every, int cycle,
                       long max_growth_kb) {
  SoakVerdict v;
  v.warmup_frames = every * cycle;
  const SoakSample* warm = nullptr;
  for (const SoakSample& s : samples)
    if (s.frame == v.warmup_frames) warm = &s;
  if (warm == nullptr || samples.empty() || samples.back().frame <= v.warmup_frames) {
    v.objects_detail = "too few frames: the soak must run past its warm-up of " +
                       std::to_string(v.warmup_frames) + " frames (one material cycle)";
    return v;
  }
  // The same point of every cycle after warm-up holds the same objects.
  const int period = every * cycle;
  v.rss_end_minus_warmup_kb = samples.back().rss_kb - warm->rss_kb;
  v.heap_growth_kb = samples.back().heap_kb - warm->heap_kb;
  const bool measured = judge_rss(samples, period, v);
  v.rss_ok = warm->rss_kb > 0 && measured && v.rss_growth_kb < max_growth_kb;
  judge_objects(samples, period, v);
  return v;
}

std::string soak_csv(const std::vector<SoakSample>& samples) {
  std::ostringstream out;
  out << "frame,rss_kb,vk_objects,heap_kb,material\n";
  for (const SoakSample& s : samples)
    out << s.frame << ',' << s.rss_kb << ',' << s.vk_objects << ',' << s.heap_kb << ','
        << s.material << '\n';
  return out.str();
}

std::string soak_svg(const std::vector<SoakSample>& samples, const SoakVerdict& verdict,
                     const std::string& title) {
  constexpr double kW = 900, kLeft = 90, kRight = 30, kTop = 50, kPanel = 220, kGap = 70;
  const double kH = kTop + 2 * kPanel + kGap + 80;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kW << "\" height=\"" << kH
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << kW / 2 << "\" y=\"28\" text-anchor=\"middle\" font-size=\"15\">" << title
      << "</text>\n";
  if (samples.empty()) {
    svg << "</svg>\n";
    return svg.str();
  }
  const double x_max = std::max(1, samples.back().frame);
  const auto px = [&](double f) { return kLeft + f / x_max * (kW - kLeft - kRight); };
  // One panel: a line of y(sample) with its own linear axis.
  const auto panel = [&](double top, const std::string& y_label, const std::string& color,
                         auto value) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const SoakSample& s : samples) {
      lo = std::min(lo, value(s));
      hi = std::max(hi, value(s));
    }
    if (!(hi > lo)) {  // a flat line (the object count, ideally): give it room to show
      const double pad = std::max(1.0, 0.05 * std::abs(lo));
      lo -= pad;
      hi += pad;
    }
    const double step = tick_step(lo, hi);
    lo = std::floor(lo / step) * step;
    hi = std::max(std::ceil(hi / step) * step, lo + step);
    const auto py = [&](double y) { return top + kPanel - (y - lo) / (hi - lo) * kPanel; };
    svg << "<rect x=\"" << kLeft << "\" y=\"" << top << "\" width=\"" << kW - kLeft - kRight
        << "\" height=\"" << kPanel << "\" fill=\"none\" stroke=\"#444\"/>\n";
    for (double y = lo; y <= hi + step * 1e-6; y += step)
      svg << "<line x1=\"" << kLeft - 4 << "\" x2=\"" << kW - kRight << "\" y1=\"" << num(py(y))
          << "\" y2=\"" << num(py(y)) << "\" stroke=\"#ddd\"/><text x=\"" << kLeft - 8
          << "\" y=\"" << num(py(y) + 4) << "\" text-anchor=\"end\">" << label(y) << "</text>\n";
    const double xs = tick_step(0.0, x_max);
    for (double x = 0.0; x <= x_max + 1e-6; x += xs)
      svg << "<text x=\"" << num(px(x)) << "\" y=\"" << top + kPanel + 16
          << "\" text-anchor=\"middle\">" << label(x) << "</text>\n";
    svg << "<text x=\"18\" y=\"" << top + kPanel / 2 << "\" transform=\"rotate(-90 18 "
        << top + kPanel / 2 << ")\" text-anchor=\"middle\">" << y_label << "</text>\n";
    if (verdict.warmup_frames > 0 && verdict.warmup_frames <= x_max)
      svg << "<line x1=\"" << num(px(verdict.warmup_frames)) << "\" x2=\""
          << num(px(verdict.warmup_frames)) << "\" y1=\"" << top << "\" y2=\"" << top + kPanel
          << "\" stroke=\"#888\" stroke-dasharray=\"5,4\"/><text x=\""
          << num(px(verdict.warmup_frames) + 4) << "\" y=\"" << top + 14
          << "\" fill=\"#666\">end of warm-up</text>\n";
    svg << "<polyline fill=\"none\" stroke=\"" << color << "\" stroke-width=\"1.5\" points=\"";
    for (const SoakSample& s : samples) svg << num(px(s.frame)) << ',' << num(py(value(s))) << ' ';
    svg << "\"/>\n";
  };
  panel(kTop, "resident memory (MB)", "#c0392b",
        [](const SoakSample& s) { return double(s.rss_kb) / 1024.0; });
  panel(kTop + kPanel + kGap, "live Vulkan objects", "#2c6fbb",
        [](const SoakSample& s) { return double(s.vk_objects); });
  svg << "<text x=\"" << (kLeft + kW - kRight) / 2 << "\" y=\"" << kH - 40
      << "\" text-anchor=\"middle\">frame</text>\n"
      << "<text x=\"" << kLeft << "\" y=\"" << kH - 14 << "\">RSS peak growth after warm-up "
      << verdict.rss_growth_kb << " kB (end minus warm-up " << verdict.rss_end_minus_warmup_kb
      << " kB, live heap " << verdict.heap_growth_kb << " kB); "
      << (verdict.objects_ok ? "Vulkan objects: no leak" : "Vulkan objects: LEAK") << "</text>\n"
      << "</svg>\n";
  return svg.str();
}

namespace {

constexpr auto kFitTimeout = std::chrono::minutes(2);

struct SoakTimes {
  double render_ms = 0.0, refit_ms = 0.0, readback_ms = 0.0, total_s = 0.0;
};

// The frames: every --soak-every frames a sample (read back as a screenshot would), then
// the next step of the material cycle through the panel's code, refit and applied.
SoakTimes soak_frames(const ViewerArgs& a, renderer::Renderer& r, MaterialEditor& editor,
                      std::vector<SoakSample>& samples) {
  const std::vector<int> presets = accepted_presets(editor.edits()[0]);
  if (presets.empty()) throw std::runtime_error("--soak: the material panel accepts no preset");
  const auto all = profiles::presets();
  // Step k of the cycle: the k-th accepted preset, the last step a coefficient edit.
  const auto apply_step = [&](int step) -> std::string {
    MaterialEdit& e = editor.edits()[0];
    if (step == a.soak_cycle - 1 && a.soak_cycle > 1) {
      for (float& s : e.sigma_a) s *= 1.5f;
      if (!editor.apply(0)) throw std::runtime_error("--soak: coefficient edit refused: " + e.error);
      return "coefficients";
    }
    const int preset = presets[std::size_t(step) % presets.size()];
    if (!editor.select_preset(0, preset))
      throw std::runtime_error("--soak: preset refused: " + e.error);
    return std::string(all[std::size_t(preset)].name);
  };

  SoakTimes times;
  std::string shown = "scene";
  const auto start = Clock::now();
  for (int frame = 0;; ++frame) {
    if (frame % a.soak_every == 0 || frame == a.soak) {
      if (frame > 0) {  // read the frame back, as a screenshot does
        const auto t = Clock::now();
        (void)r.read_display();
        times.readback_ms += ms_since(t);
      }
      samples.push_back({frame, resident_kb(), vk::live_object_count(), heap_kb(), shown});
      if (frame == a.soak) break;
      const auto t = Clock::now();
      shown = apply_step((frame / a.soak_every) % a.soak_cycle);
      if (!editor.wait_idle(kFitTimeout))
        throw std::runtime_error("--soak: the refit for " + shown + " did not finish");
      if (!editor.update(r))
        throw std::runtime_error("--soak: " + shown + " was not applied: " + editor.edits()[0].error);
      times.refit_ms += ms_since(t);
    }
    const auto t = Clock::now();
    r.render_frame();
    times.render_ms += ms_since(t);
    editor.frame_presented();
  }
  times.total_s = ms_since(start) / 1000.0;
  return times;
}

// The table of samples, the times and the verdict on stdout.
void print_soak_report(const ViewerArgs& a, const renderer::RenderOptions& options,
                       const std::vector<SoakSample>& samples, SoakVerdict& v,
                       const SoakTimes& times) {
  std::printf("soak: %s %ux%u, %d frames, material changed every %d frames through the panel's "
              "code, cycle of %d steps (%d frames)\n",
              a.scene.c_str(), options.width, options.height, a.soak, a.soak_every, a.soak_cycle,
              a.soak_every * a.soak_cycle);
  const int key_every = std::max(a.soak_every, (a.soak / 10 / a.soak_every) * a.soak_every);
  std::printf("%8s %10s %11s %10s  %s\n", "frame", "rss_kb", "vk_objects", "heap_kb", "material");
  for (const SoakSample& s : samples)
    if (s.frame % key_every == 0 || s.frame == a.soak || s.frame == v.warmup_frames)
      std::printf("%8d %10ld %11lld %10ld  %s\n", s.frame, s.rss_kb,
                  static_cast<long long>(s.vk_objects), s.heap_kb, s.material.c_str());
  std::printf("live Vulkan objects at the end by type:");
  for (const vk::LiveCount& c : vk::live_objects())
    if (c.live != 0) std::printf(" %.*s %lld", int(c.type.size()), c.type.data(), static_cast<long long>(c.live));
  std::printf("\n");
  std::printf("time: %.1f s; render_frame %.2f ms/frame; refit + upload %.1f ms per change; "
              "readback %.2f ms per sample\n",
              times.total_s, times.render_ms / std::max(a.soak, 1),
              times.refit_ms / std::max<std::size_t>(samples.size() - 1, 1),
              times.readback_ms / std::max<std::size_t>(samples.size() - 1, 1));
  std::printf("warm-up: the first %d frames (one material cycle)\n", v.warmup_frames);
  const char* rss_state = v.rss_ok ? "ok" : "FAIL";
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer keeps freed blocks resident (its quarantine, 256 MB by default), so
  // resident memory says nothing about leaks here; LeakSanitizer checks them at exit.
  rss_state = "not judged under AddressSanitizer";
  v.rss_ok = true;
#endif
  std::printf("RSS after warm-up: the cycle peaks' median rise x rises %+ld kB, "
              "limit %ld kB: %s (end minus warm-up %+ld kB; live heap %+ld kB)\n",
              v.rss_growth_kb, a.soak_max_growth_kb, rss_state,
              v.rss_end_minus_warmup_kb, v.heap_growth_kb);
  std::printf("Vulkan objects: %s: %s\n", v.objects_detail.c_str(), v.objects_ok ? "ok" : "FAIL");
  if (!a.soak_csv.empty()) std::printf("wrote %s\n", a.soak_csv.c_str());
  if (!a.soak_svg.empty()) std::printf("wrote %s\n", a.soak_svg.c_str());
  std::printf("soak: %s\n", v.ok() ? "pass" : "FAIL");
  std::fflush(stdout);
}

}  // namespace

int run_soak(const ViewerArgs& a, const scene::Scene& scene, const renderer::RenderOptions& options) {
  if (a.soak_every < 1 || a.soak_cycle < 1)
    return usage_error("sss-viewer", "--soak-every and --soak-cycle must be at least 1");
  vk::Context context(headless_context_options(a));
  renderer::Renderer r(context, scene, options);
  print_warnings(r);
  MaterialEditor editor(scene, options.separable_taps, FitWorker::compute_default, options.single_scattering);
  if (!editor.had_sss())
    return usage_error("sss-viewer", "--soak: the scene " + a.scene +
                                         " has no SSS material to change");
  // The editor's start-up refit of the scene's own materials (the window does the same).
  if (!editor.wait_idle(kFitTimeout)) throw std::runtime_error("--soak: the start-up fit did not finish");
  editor.update(r);

  std::vector<SoakSample> samples;
  const SoakTimes times = soak_frames(a, r, editor, samples);
  SoakVerdict v = judge_soak(samples, a.soak_every, a.soak_cycle, a.soak_max_growth_kb);
  if (!a.soak_csv.empty()) image::write_file_atomically(a.soak_csv, soak_csv(samples));
  if (!a.soak_svg.empty()) {
    std::ostringstream title;
    title << "sss-viewer --soak " << a.soak << ": " << a.scene << " " << options.width << "x"
          << options.height << ", material changed every " << a.soak_every << " frames, cycle of "
          << a.soak_cycle;
    image::write_file_atomically(a.soak_svg, soak_svg(samples, v, title.str()));
  }
  if (!a.out.empty()) write_frame(r, a.out);
  print_soak_report(a, options, samples, v, times);
  return v.ok() ? kExitOk : kExitRuntime;
}

}  // namespace sss::app
