// The soak (issue 7, "Soak and faults"): `sss-viewer [SCENE] --headless --soak N` renders N
// frames headless and changes the first SSS material every --soak-every frames through
// the material panel's own code (MaterialEditor: select_preset / the coefficient fields +
// apply, the FitWorker thread, update() -> Renderer::set_materials), cycling through
// --soak-cycle steps: the presets the editor accepts, in order, then one coefficient edit
// (the last preset's sigma_a x 1.5, which makes the source "coefficients").
//
// Every --soak-every frames (before that frame's change) it reads the frame back (as a
// screenshot does), then records the resident memory (VmRSS of /proc/self/status) and
// the live Vulkan objects (vk::live_object_count(), Handle.h), and the live malloc heap
// (mallinfo2: in use + mmapped, every arena). Warm-up is the first full material cycle
// (every x cycle frames): each step's first fit and upload, the driver's first pipelines
// and malloc's high-water marks happen there. It passes when
//   - resident memory grows by less than --soak-max-growth-kb (default 1024: the issue's
//     "grows by less than 1 MB") from the first cycle after warm-up to the last cycle,
//     each cycle taken at its peak. The peaks, not two single samples: glibc keeps freed
//     blocks (the 0.9 MB frame read back at 320x180 for instance), so RSS swings by
//     ~1.4 MB between samples of a run whose live heap does not grow (measured: 10,000
//     bunny frames, the floor 112536 kB from frame 1100 to 8500); a leak lifts the peaks
//     as much as the floor. The end-minus-warm-up difference and the heap are printed;
//   - the live object count at every sample after warm-up equals the count at the same
//     point of the first cycle after warm-up (the same work holds the same objects).
// Writes the samples as CSV (frame,rss_kb,vk_objects,heap_kb,material) and an SVG plot of RSS
// and objects against frames; prints the curve's key points and the verdict.
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
  // The criterion: the peak RSS of each material cycle after warm-up (a last, partial
  // cycle counts as one), the lower median of the rises from one cycle's peak to the next
  // (the smaller of two, the 3rd smallest of six), times the number of rises. A leak rises
  // in every cycle, so it shows in full (a steady 1 MB over the run gives 1 MB). Steps that
  // are not leaks rise in fewer than half of the cycles and do not show: an allocator
  // arena or a validation layer's cache growing once (+3.1 MB in one CI run under the
  // synchronization layer), or RSS rising in two cycles running (+2.2 MB, +2.8 MB in one
  // CI run under best practices, while 1,600 frames on the same build rose in none).
  // With two cycles (one rise) it is last peak minus first.
  // Also the plain end-minus-warm-up difference (reported).
  long rss_growth_kb = 0;
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

// The verdict on the samples (taken every `every` frames, a cycle being `cycle` steps).
SoakVerdict judge_soak(const std::vector<SoakSample>& samples, int every, int cycle,
                       long max_growth_kb);

// The CSV and the SVG document of the samples.
std::string soak_csv(const std::vector<SoakSample>& samples);
std::string soak_svg(const std::vector<SoakSample>& samples, const SoakVerdict& verdict,
                     const std::string& title);

// Runs the soak headless; returns the exit code (0 pass, 1 a criterion failed or a
// runtime error, 2 bad input such as a scene without an SSS material).
int run_soak(const ViewerArgs& a, const scene::Scene& scene, const renderer::RenderOptions& options);

}  // namespace sss::app
