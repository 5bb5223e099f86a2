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

// The memory verdict needs this many full cycles after warm-up (three a half, so that each
// half's line has a residual to estimate its error from).
inline constexpr int kSoakMinCycles = 6;
// Each half's one-sided level: both halves must grow for a run to fail, so a run whose
// memory grows by exactly the limit fails (1 - 0.968377)^2 = 0.001 of the time.
inline constexpr double kSoakHalfLevel = 0.9683772233983162;  // 1 - sqrt(0.001)

struct SoakVerdict {
  int warmup_frames = 0;
  // The memory criterion. Each full material cycle after warm-up is summed up by the
  // median of VmRSS read after each of its frames (a leak lifts every reading of a cycle,
  // so it lifts the median by what has leaked; the frames' own swing does not: lavapipe's
  // binning and the allocator make RSS swing by 5 to 10 MB from frame to frame at 160x90,
  // and a sample taken every 50 frames, or a cycle's peak, moved by 1 to 3 MB from cycle
  // to cycle with no leak). A leak grows linearly with the cycles. The medians of a run
  // without one still scatter by 0.7 to 1.6 MB (states of the allocator and the driver
  // that last tens of frames), and RSS can also step up once and stay (an allocator
  // arena, a layer's cache): a step is not a leak, but a line through a run with a step
  // in its middle rises as steeply as a leak of that size. So:
  //   - each half of the cycles (the first n/2, then the rest) gets its own least-squares
  //     line through its medians: its slope times (cycles - 1), the growth over the whole
  //     run that the half implies, with the standard error from the half's residuals
  //     (m - 2 degrees of freedom);
  //   - the run fails when both halves grow significantly by the limit or more:
  //     growth - t x error >= max_growth_kb in each, t the one-sided kSoakHalfLevel
  //     quantile of Student's t with m - 2 degrees of freedom. A leak grows in both
  //     halves; a one-time step lies in one (a step between the halves in neither). A run
  //     whose memory grows by exactly the limit fails 1 time in 1,000 under independent
  //     Gaussian scatter (tested by simulation in SoakVerdict.TheGrowthTestFailsAtItsLevel).
  //   - half[h].detectable_kb = max_growth_kb + t x that half's error is the growth that
  //     half flags with probability one half.
  // rss_growth_kb and rss_growth_se_kb are the same line through all the medians, shown
  // on the plot and printed; they do not decide. Fewer than kSoakMinCycles cycles: not
  // judged (rss_judged false, and rss_ok says only whether /proc could be read).
  // Also the plain end-minus-warm-up difference of the samples (reported).
  struct Half {
    long growth_kb = 0, se_kb = 0, detectable_kb = 0;
    double t = 0.0;
  };
  long rss_growth_kb = 0;
  long rss_growth_se_kb = 0;
  Half half[2];
  bool rss_judged = false;
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
