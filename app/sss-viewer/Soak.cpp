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
#include <stdexcept>

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

// Student's t by Abramowitz & Stegun 26.7.3 (odd dof) and 26.7.4 (even dof): with
// theta = atan(t / sqrt(dof)), A(t | dof) = P(|T| <= t) is a finite sum in cos(theta), and
// P(T <= t) = (1 + A) / 2. The quantile: bisection on theta in (0, pi/2), where A rises
// from 0 to 1.
double student_t_quantile(double p, int dof) {
  if (!(p > 0.5 && p < 1.0) || dof < 1)
    throw std::invalid_argument("student_t_quantile: needs 0.5 < p < 1 and dof >= 1");
  const double pi = std::acos(-1.0);
  const auto a_of = [dof, pi](double theta) {
    const double c2 = std::cos(theta) * std::cos(theta), sn = std::sin(theta);
    if (dof % 2 == 1) {
      double sum = 0.0, term = std::cos(theta);  // cos + (2/3) cos^3 + (2 4)/(3 5) cos^5 ...
      for (int k = 1; 2 * k - 1 <= dof - 2; ++k) {
        sum += term;
        term *= c2 * (2.0 * k) / (2.0 * k + 1.0);
      }
      return 2.0 / pi * (theta + sn * sum);
    }
    double sum = 0.0, term = 1.0;  // 1 + (1/2) cos^2 + (1 3)/(2 4) cos^4 ...
    for (int k = 0; 2 * k <= dof - 2; ++k) {
      sum += term;
      term *= c2 * (2.0 * k + 1.0) / (2.0 * k + 2.0);
    }
    return sn * sum;
  };
  const double target = 2.0 * p - 1.0;  // A at the quantile
  double lo = 0.0, hi = pi / 2.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (a_of(mid) < target ? lo : hi) = mid;
  }
  return std::sqrt(double(dof)) * std::tan(0.5 * (lo + hi));
}

namespace {

double median_of(std::vector<long> v) {
  if (v.empty()) return 0.0;
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(m), v.end());
  if (v.size() % 2 == 1) return double(v[m]);
  const long below = *std::max_element(v.begin(), v.begin() + std::ptrdiff_t(m));
  return 0.5 * (double(below) + double(v[m]));
}

// The readings after frames first + 1 .. last (frame_rss_kb[i] is after frame i + 1).
std::vector<long> readings(const std::vector<long>& frame_rss_kb, int first, int last) {
  last = std::min(last, int(frame_rss_kb.size()));
  if (first >= last) return {};
  return {frame_rss_kb.begin() + first, frame_rss_kb.begin() + last};
}

// A least-squares line through y[0 .. n) against k = 0 .. n - 1, as a growth over `span`
// cycles (slope x span) and that growth's standard error from the residuals (n >= 3).
struct LineFit {
  double growth = 0.0, se = 0.0;
};
LineFit fit_line(const long* y, std::size_t n, double span) {
  const double k_mean = double(n - 1) / 2.0;
  double y_mean = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t k = 0; k < n; ++k) y_mean += double(y[k]) / double(n);
  for (std::size_t k = 0; k < n; ++k) {
    sxx += (double(k) - k_mean) * (double(k) - k_mean);
    sxy += (double(k) - k_mean) * (double(y[k]) - y_mean);
  }
  const double b = sxy / sxx;
  double ssr = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double r = double(y[k]) - (y_mean + b * (double(k) - k_mean));
    ssr += r * r;
  }
  return {b * span, span * std::sqrt(ssr / double(n - 2) / sxx)};
}

// The memory criterion (SoakVerdict::rss_growth_kb): the medians of the full cycles after
// warm-up, the growth of each half and the verdict.
void judge_rss(const std::vector<long>& frame_rss_kb, int period, long max_growth_kb,
               SoakVerdict& v) {
  for (int start = v.warmup_frames; start + period <= int(frame_rss_kb.size()); start += period)
    v.cycle_median_kb.push_back(std::lround(median_of(readings(frame_rss_kb, start, start + period))));
  const bool read = std::all_of(frame_rss_kb.begin(), frame_rss_kb.end(), [](long r) { return r > 0; });
  const std::vector<long>& y = v.cycle_median_kb;
  const std::size_t n = y.size();
  if (n < std::size_t(kSoakMinCycles)) {
    v.rss_judged = false;
    v.rss_ok = read;
    return;
  }
  const double span = double(n - 1);
  const LineFit all = fit_line(y.data(), n, span);
  v.rss_growth_kb = std::lround(all.growth);
  v.rss_growth_se_kb = std::lround(all.se);
  v.rss_judged = true;
  bool grows = true;
  const std::size_t first = n / 2;  // the first half's cycles; the second has the rest
  for (int h = 0; h < 2; ++h) {
    const std::size_t m = h == 0 ? first : n - first;
    const LineFit half = fit_line(y.data() + (h == 0 ? 0 : first), m, span);
    v.half[h].growth_kb = std::lround(half.growth);
    v.half[h].se_kb = std::lround(half.se);
    v.half[h].t = student_t_quantile(kSoakHalfLevel, int(m) - 2);
    v.half[h].detectable_kb = std::lround(double(max_growth_kb) + v.half[h].t * half.se);
    grows = grows && half.growth - v.half[h].t * half.se >= double(max_growth_kb);
  }
  v.rss_ok = read && !grows;
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

SoakVerdict judge_soak(const std::vector<SoakSample>& samples,
                       const std::vector<long>& frame_rss_kb, int every, int cycle,
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
  judge_rss(frame_rss_kb, period, max_growth_kb, v);
  judge_objects(samples, period, v);
  return v;
}

std::string soak_csv(const std::vector<SoakSample>& samples, const std::vector<long>& frame_rss_kb) {
  std::ostringstream out;
  out << "frame,rss_kb,rss_median_kb,vk_objects,heap_kb,material\n";
  int previous = 0;
  for (const SoakSample& s : samples) {
    // The median of the readings after the frames since the previous sample (none at 0).
    const std::vector<long> since = readings(frame_rss_kb, previous, s.frame);
    out << s.frame << ',' << s.rss_kb << ',';
    if (!since.empty()) out << std::lround(median_of(since));
    out << ',' << s.vk_objects << ',' << s.heap_kb << ',' << s.material << '\n';
    previous = s.frame;
  }
  return out.str();
}

namespace {

using Points = std::vector<std::pair<double, double>>;  // (frame, value)

// The soak plot's layout: panels one above the other over frames 0 .. x_max, each with its own
// y axis.
struct SoakPlot {
  static constexpr double kW = 900, kLeft = 90, kRight = 30, kTop = 50, kPanel = 220, kGap = 70;
  double x_max = 1.0;
  int warmup_frames = 0;
  double px(double frame) const { return kLeft + frame / x_max * (kW - kLeft - kRight); }
};

// One panel at `top`: a line through `points` with its own linear axis; overlay(py) draws
// more in the panel's coordinates.
template <class Overlay>
void svg_panel(std::ostringstream& svg, const SoakPlot& plot, double top, const std::string& y_label,
               const std::string& color, const Points& points, Overlay overlay) {
  using P = SoakPlot;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& [x, y] : points) {
    lo = std::min(lo, y);
    hi = std::max(hi, y);
  }
  if (!(hi > lo)) {  // a flat line (the object count, ideally): give it room to show
    const double pad = std::max(1.0, 0.05 * std::abs(lo));
    lo -= pad;
    hi += pad;
  }
  const double step = tick_step(lo, hi);
  lo = std::floor(lo / step) * step;
  hi = std::max(std::ceil(hi / step) * step, lo + step);
  const auto py = [&](double y) { return top + P::kPanel - (y - lo) / (hi - lo) * P::kPanel; };
  svg << "<rect x=\"" << P::kLeft << "\" y=\"" << top << "\" width=\"" << P::kW - P::kLeft - P::kRight
      << "\" height=\"" << P::kPanel << "\" fill=\"none\" stroke=\"#444\"/>\n";
  for (double y = lo; y <= hi + step * 1e-6; y += step)
    svg << "<line x1=\"" << P::kLeft - 4 << "\" x2=\"" << P::kW - P::kRight << "\" y1=\"" << num(py(y))
        << "\" y2=\"" << num(py(y)) << "\" stroke=\"#ddd\"/><text x=\"" << P::kLeft - 8
        << "\" y=\"" << num(py(y) + 4) << "\" text-anchor=\"end\">" << label(y) << "</text>\n";
  const double xs = tick_step(0.0, plot.x_max);
  for (double x = 0.0; x <= plot.x_max + 1e-6; x += xs)
    svg << "<text x=\"" << num(plot.px(x)) << "\" y=\"" << top + P::kPanel + 16
        << "\" text-anchor=\"middle\">" << label(x) << "</text>\n";
  svg << "<text x=\"18\" y=\"" << top + P::kPanel / 2 << "\" transform=\"rotate(-90 18 "
      << top + P::kPanel / 2 << ")\" text-anchor=\"middle\">" << y_label << "</text>\n";
  const double warm = plot.px(plot.warmup_frames);
  if (plot.warmup_frames > 0 && plot.warmup_frames <= plot.x_max)
    svg << "<line x1=\"" << num(warm) << "\" x2=\"" << num(warm) << "\" y1=\"" << top << "\" y2=\""
        << top + P::kPanel << "\" stroke=\"#888\" stroke-dasharray=\"5,4\"/><text x=\""
        << num(warm + 4) << "\" y=\"" << top + 14 << "\" fill=\"#666\">end of warm-up</text>\n";
  svg << "<polyline fill=\"none\" stroke=\"" << color << "\" stroke-width=\"1\" points=\"";
  for (const auto& [x, y] : points) svg << num(plot.px(x)) << ',' << num(py(y)) << ' ';
  svg << "\"/>\n";
  overlay(py);
}

}  // namespace

std::string soak_svg(const std::vector<SoakSample>& samples, const std::vector<long>& frame_rss_kb,
                     const SoakVerdict& verdict, const std::string& title) {
  using P = SoakPlot;
  const double kH = P::kTop + 2 * P::kPanel + P::kGap + 120;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << P::kW << "\" height=\"" << kH
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << P::kW / 2 << "\" y=\"28\" text-anchor=\"middle\" font-size=\"15\">" << title
      << "</text>\n";
  if (samples.empty()) {
    svg << "</svg>\n";
    return svg.str();
  }
  const SoakPlot plot{double(std::max(1, samples.back().frame)), verdict.warmup_frames};
  // RSS after every frame, with each cycle's median (a dot at the cycle's middle) and the
  // least-squares line through them that the verdict judges.
  Points rss;
  for (std::size_t i = 0; i < frame_rss_kb.size(); ++i)
    rss.emplace_back(double(i + 1), double(frame_rss_kb[i]) / 1024.0);
  if (rss.empty())
    for (const SoakSample& s : samples) rss.emplace_back(s.frame, double(s.rss_kb) / 1024.0);
  const std::vector<long>& med = verdict.cycle_median_kb;
  const double period = double(verdict.warmup_frames);  // the warm-up is one cycle
  const auto mid = [&](std::size_t k) { return double(verdict.warmup_frames) + (double(k) + 0.5) * period; };
  svg_panel(svg, plot, P::kTop, "resident memory (MB)", "#e3a59c", rss, [&](auto py) {
    for (std::size_t k = 0; k < med.size(); ++k)
      svg << "<circle cx=\"" << num(plot.px(mid(k))) << "\" cy=\"" << num(py(double(med[k]) / 1024.0))
          << "\" r=\"4\" fill=\"#8e1b10\"/>\n";
    // A line through cycles [k0, k1): through their mean at their middle, rising by `growth`
    // over the whole run (cycles - 1).
    const auto fit = [&](std::size_t k0, std::size_t k1, double growth, const char* style) {
      double mean = 0.0;
      for (std::size_t k = k0; k < k1; ++k) mean += double(med[k]) / double(k1 - k0);
      const double per_cycle = growth / double(med.size() - 1), centre = double(k0 + k1 - 1) / 2.0;
      const auto y = [&](std::size_t k) { return (mean + per_cycle * (double(k) - centre)) / 1024.0; };
      svg << "<line x1=\"" << num(plot.px(mid(k0))) << "\" y1=\"" << num(py(y(k0))) << "\" x2=\""
          << num(plot.px(mid(k1 - 1))) << "\" y2=\"" << num(py(y(k1 - 1))) << "\" stroke=\"#8e1b10\" "
          << style << "/>\n";
    };
    if (verdict.rss_judged) {  // the two halves' lines decide; the whole run's is drawn thin
      fit(0, med.size(), double(verdict.rss_growth_kb), "stroke-width=\"1\" stroke-dasharray=\"4,3\"");
      fit(0, med.size() / 2, double(verdict.half[0].growth_kb), "stroke-width=\"2.5\"");
      fit(med.size() / 2, med.size(), double(verdict.half[1].growth_kb), "stroke-width=\"2.5\"");
    }
  });
  Points objects;
  for (const SoakSample& s : samples) objects.emplace_back(s.frame, double(s.vk_objects));
  svg_panel(svg, plot, P::kTop + P::kPanel + P::kGap, "live Vulkan objects", "#2c6fbb", objects,
            [](auto) {});
  svg << "<text x=\"" << (P::kLeft + P::kW - P::kRight) / 2 << "\" y=\"" << kH - 80
      << "\" text-anchor=\"middle\">frame</text>\n"
      << "<text x=\"" << P::kLeft << "\" y=\"" << kH - 54 << "\">Dots: each cycle's median RSS; "
      << "thick lines: least squares through each half of the cycles, dashed: through all</text>\n"
      << "<text x=\"" << P::kLeft << "\" y=\"" << kH - 34 << "\">Growth over the run by the halves "
      << verdict.half[0].growth_kb << " \u00b1 " << verdict.half[0].se_kb << " and "
      << verdict.half[1].growth_kb << " \u00b1 " << verdict.half[1].se_kb << " kB, by all "
      << verdict.rss_growth_kb << " \u00b1 " << verdict.rss_growth_se_kb << " kB</text>\n"
      << "<text x=\"" << P::kLeft << "\" y=\"" << kH - 14 << "\">(end minus warm-up "
      << verdict.rss_end_minus_warmup_kb << " kB, live heap " << verdict.heap_growth_kb << " kB); "
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
                      std::vector<SoakSample>& samples, std::vector<long>& frame_rss_kb) {
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
    frame_rss_kb[std::size_t(frame)] = resident_kb();  // a read of /proc: ~30 us a frame
  }
  times.total_s = ms_since(start) / 1000.0;
  return times;
}

// The memory verdict's figures (SoakVerdict) on stdout.
void print_rss_verdict(const SoakVerdict& v, long limit_kb, const char* state) {
  std::printf("RSS medians of the %zu full cycles after warm-up (kB):", v.cycle_median_kb.size());
  for (long m : v.cycle_median_kb) std::printf(" %ld", m);
  std::printf("\n");
  if (!v.rss_judged) {
    std::printf("RSS: not judged: %zu full cycles after warm-up, %d needed (--soak of at least "
                "%d cycles: warm-up + %d)\n",
                v.cycle_median_kb.size(), kSoakMinCycles, kSoakMinCycles + 1, kSoakMinCycles);
    return;
  }
  std::printf("RSS growth over the run (least squares through all medians) %+ld kB, standard "
              "error %ld kB\n", v.rss_growth_kb, v.rss_growth_se_kb);
  const std::size_t first = v.cycle_median_kb.size() / 2;
  for (int h = 0; h < 2; ++h)
    std::printf("  %s half (%zu cycles): the run's growth by its line %+ld kB, error %ld kB, "
                "t %.2f: flags growth of about %ld kB or more\n", h == 0 ? "first" : "second",
                h == 0 ? first : v.cycle_median_kb.size() - first, v.half[h].growth_kb,
                v.half[h].se_kb, v.half[h].t, v.half[h].detectable_kb);
  std::printf("RSS fails when both halves' growth - t x error >= %ld kB (each one-sided 96.8%%, "
              "together 99.9%%; a one-time step lies in one half): %s\n", limit_kb, state);
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
  print_rss_verdict(v, a.soak_max_growth_kb, rss_state);
  std::printf("(end minus warm-up %+ld kB; live heap %+ld kB)\n", v.rss_end_minus_warmup_kb,
              v.heap_growth_kb);
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
  // Filled (so resident) before the first frame: growing it would add 8 bytes a frame.
  std::vector<long> frame_rss_kb(std::size_t(a.soak), 0);
  const SoakTimes times = soak_frames(a, r, editor, samples, frame_rss_kb);
  SoakVerdict v = judge_soak(samples, frame_rss_kb, a.soak_every, a.soak_cycle, a.soak_max_growth_kb);
  if (!a.soak_csv.empty()) image::write_file_atomically(a.soak_csv, soak_csv(samples, frame_rss_kb));
  if (!a.soak_svg.empty()) {
    std::ostringstream title;
    title << "sss-viewer --soak " << a.soak << ": " << a.scene << " " << options.width << "x"
          << options.height << ", material changed every " << a.soak_every << " frames, cycle of "
          << a.soak_cycle;
    image::write_file_atomically(a.soak_svg, soak_svg(samples, frame_rss_kb, v, title.str()));
  }
  if (!a.out.empty()) write_frame(r, a.out);
  print_soak_report(a, options, samples, v, times);
  return v.ok() ? kExitOk : kExitRuntime;
}

}  // namespace sss::app
