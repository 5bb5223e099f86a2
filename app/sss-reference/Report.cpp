#include "Report.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sss::app {

std::string duration(double seconds) {
  char buf[32];
  const long s = long(std::lround(std::max(seconds, 0.0)));
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  else if (s >= 60) std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%lds", s);
  return buf;
}

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled), tty_(isatty(STDERR_FILENO) == 1) {}

void ProgressBar::operator()(const char* stage, double fraction) {
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

}  // namespace sss::app
