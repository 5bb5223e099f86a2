// The soak (issue 7, "Soak and faults"): `sss-viewer [SCENE] --headless --soak N` renders N
// frames headless and changes the first SSS material every --soak-every frames through
// the material panel's own code (MaterialEditor: select_preset / the coefficient fields +
// apply, the FitWorker thread, update() -> Renderer::set_materials), cycling through
// --soak-cycle steps: the presets the editor accepts, in order, then one coefficient edit
// (the last preset's sigma_a x 1.5, which makes the source "coefficients").
//
// Every --soak-every frames (before that frame's change) it reads the frame back (as a
// screenshot does) and records a sample: the resident memory (VmRSS of /proc/self/status),
// the live Vulkan objects (vk::live_object_count(), Handle.h) and the live malloc heap
// (mallinfo2: in use + mmapped, every arena). It also reads VmRSS after every frame. Warm-up
// is the first full material cycle (every x cycle frames): each step's first fit and
// upload, the driver's first pipelines and malloc's high-water marks happen there. It
// passes when
//   - resident memory does not grow by --soak-max-growth-kb (default 1024: the issue's
//     "grows by less than 1 MB") or more over the cycles after warm-up, within what the
//     run can resolve: see SoakVerdict::rss_growth_kb for the statistics;
//   - the live object count at every sample after warm-up equals the count at the same
//     point of the first cycle after warm-up (the same work holds the same objects).
// Writes the samples as CSV (frame,rss_kb,rss_median_kb,vk_objects,heap_kb,material) and an
// SVG plot of RSS (every frame, the cycle medians and their fitted line) and objects against
// frames; prints the curve's key points and the verdict.
#pragma once

#include "ViewerArgs.h"

#include "renderer/RenderOptions.h"
#include "scene/Scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace sss::app {

struct SoakSample {
  int frame = 0;             // frames rendered before the sample
  long rss_kb = 0;           // VmRSS
  std::int64_t vk_objects = 0;
  long heap_kb = 0;          // bytes malloc has handed out and not got back (mallinfo2)
  std::string material;      // the step shown in the frames before the sample
};

struct SoakVerdict {
  int warmup_frames = 0;
  // The memory criterion. Each full material cycle after warm-up is summed up by the
  // median of VmRSS read after each of its frames (a leak lifts every reading of a cycle,
  // so it lifts the median by what has leaked; the frames' own swing does not: lavapipe's
  // binning and the allocator make RSS swing by 5 to 10 MB from frame to frame at 160x90,
  // and a sample taken every 50 frames, or a cycle's peak, moved by 1 to 3 MB from cycle
  // to cycle with no leak). A leak grows linearly with the cycles, so the growth over the
  // run is the least-squares slope of the medians against the cycle index times
  // (cycles - 1), with the slope's standard error from the residuals (n - 2 degrees of
  // freedom): rss_growth_kb and rss_growth_se_kb. The medians of a run without a leak
  // still scatter by about 1 MB (states of the allocator and the driver that last tens of
  // frames), so a short run cannot tell 1 MB from 0: the run fails when the growth is
  // significantly at or above the limit, rss_growth_kb - t x rss_growth_se_kb >=
  // max_growth_kb, t the one-sided 99.9% quantile of Student's t with cycles - 2 degrees
  // of freedom (a run whose memory grows by exactly the limit fails 1 time in 1,000 under
  // Gaussian scatter; tested by simulation in SoakVerdict.TheGrowthTestFailsAtItsLevel).
  // rss_detectable_kb = max_growth_kb + t x se is the growth the run fails with
  // probability one half. Two cycles: the growth is the second median minus the first, no
  // error, and fails at >= max_growth_kb; one cycle: nothing to compare (0).
  // Also the plain end-minus-warm-up difference of the samples (reported).
  long rss_growth_kb = 0;
  long rss_growth_se_kb = 0;
  long rss_detectable_kb = 0;
  double rss_t = 0.0;                // the t quantile used (0 with fewer than 3 cycles)
  std::vector<long> cycle_median_kb; // one per full cycle after warm-up
  long rss_end_minus_warmup_kb = 0;
  long heap_growth_kb = 0;     // live malloc bytes, end minus end of warm-up
  bool rss_ok = false;
  bool objects_ok = false;
  std::string objects_detail;  // the first mismatch, or the counts per cycle point
  bool ok() const { return rss_ok && objects_ok; }
};

// Resident set size of this process in kB (VmRSS), or -1 when /proc is unreadable.
long resident_kb();
// The bytes malloc has handed out and not got back, in kB (mallinfo2, all arenas).
long heap_kb();

// The quantile p (0.5 < p < 1) of Student's t distribution with dof >= 1 degrees of freedom.
double student_t_quantile(double p, int dof);

// The verdict on the samples (taken every `every` frames, a cycle being `cycle` steps) and
// frame_rss_kb, VmRSS read after each frame (element i after frame i + 1).
SoakVerdict judge_soak(const std::vector<SoakSample>& samples,
                       const std::vector<long>& frame_rss_kb, int every, int cycle,
                       long max_growth_kb);

// The CSV and the SVG document of the samples.
std::string soak_csv(const std::vector<SoakSample>& samples, const std::vector<long>& frame_rss_kb);
std::string soak_svg(const std::vector<SoakSample>& samples, const std::vector<long>& frame_rss_kb,
                     const SoakVerdict& verdict, const std::string& title);

// Runs the soak headless; returns the exit code (0 pass, 1 a criterion failed or a
// runtime error, 2 bad input such as a scene without an SSS material).
int run_soak(const ViewerArgs& a, const scene::Scene& scene, const renderer::RenderOptions& options);

}  // namespace sss::app
