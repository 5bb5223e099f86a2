// The viewer's "Tools" window (top right, beside the material panels of Ui.h):
//   - Open: a glTF/GLB by path (or dropped on the window; Window.cpp reloads it);
//   - Compare: the CPU reference (reference) renders the current view on a
//     worker thread with progress; then the frame can be shown split A/B against it,
//     as the reference alone, or as an error map, with the metrics of sss-compare. A
//     stored ground truth (an EXR of `sss-reference --method random-walk`, the view's
//     size) can be loaded beside it: then the same metrics and maps for frame vs truth
//     and reference vs truth. The error map is the absolute error (the heat map of
//     sss-compare --heatmap) or the signed log ratio log2(A/B) of the luminance (that of
//     sss-compare --log-ratio), for the chosen pair;
//   - Export: the current SSS materials into a new glTF (extras.sss, GltfExport.h; for
//     built-in scenes a JSON of the blocks), and a material's kernel as JSON or C header
//     (the format of `sss-fit fit --out`). Nothing is ever overwritten silently.
// Every file is written atomically (image::write_file_atomically).
#pragma once

#include "image/HeatMap.h"
#include "image/Image.h"
#include "image/Metrics.h"
#include "reference/ReferenceRenderer.h"
#include "scene/Scene.h"
#include "renderer/vk/Image.h"

#include <array>
#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace sss::vk {
class Context;
}
namespace sss::renderer {
class Renderer;
}

namespace sss::app {

// What the window shows now: the loaded scene with the live materials, lights and view.
struct LiveState {
  const scene::Scene* scene = nullptr;  // meshes, textures, instances as loaded
  std::string source;                   // the path, or builtin:NAME
  const std::vector<scene::Material>& materials;  // the panels' (not copied per frame)
  const std::vector<scene::Light>& lights;
  // The window's framebuffer: the size of the reference (the renderer may draw a scaled
  // frame while the view moves).
  std::uint32_t width = 0, height = 0;
  // The files the scene was loaded from (InputFiles.h): no export may replace them.
  const std::vector<std::filesystem::path>* inputs = nullptr;
};

// The CPU reference of one view, rendered on a worker thread. Destroying or starting
// another cancels the running one (render_reference checks between rows).
class ReferenceJob {
 public:
  ReferenceJob() = default;
  ~ReferenceJob() { cancel(); }
  ReferenceJob(const ReferenceJob&) = delete;
  ReferenceJob& operator=(const ReferenceJob&) = delete;

  // choose: pick the estimator for this view first (reference::choose_estimator, as
  // sss-reference --estimator auto does), then render with it.
  void start(scene::Scene scene, const reference::ReferenceOptions& options, bool choose = false);
  void cancel();  // waits for the worker to stop
  bool running() const { return running_.load(); }
  // "points 42%" while running.
  std::string progress() const;
  double fraction() const;
  // The finished image, once (then empty); or the error of a failed run.
  std::optional<reference::ReferenceImage> take();
  std::string take_error();
  // With choose: what was chosen and why, once chosen (else empty).
  std::string chosen() const;

 private:
  std::thread worker_;
  std::atomic<bool> cancel_{false}, running_{false};
  mutable std::mutex mutex_;
  std::string stage_;
  double fraction_ = 0.0;
  std::optional<reference::ReferenceImage> result_;
  std::string error_;
  std::string chosen_;
};

class ViewerTools {
 public:
  explicit ViewerTools(const vk::Context& context) : context_(context) {}

  // Draws the Tools window (between ImGui::NewFrame and ImGui::Render). The state must
  // be what the renderer draws now. Returns a path when the user asked to open one.
  std::optional<std::string> draw(renderer::Renderer& r, const LiveState& live);

  // The "Render reference of this view" button: starts the CPU reference of what the
  // renderer draws now (same camera, size, exposure, materials and lights).
  void start_reference(const renderer::Renderer& r, const LiveState& live);
  bool reference_running() const { return job_.running(); }
  // The panel's estimator: auto (the default: choose per view, as sss-reference does),
  // the octree at the spacing slider's value, or the probe at its default batches.
  enum class ReferenceEstimator { Auto, Octree, Probe };
  void set_reference_estimator(ReferenceEstimator e) { estimator_ = int(e); }
  // Auto's choice for the last reference started ("octree at spacing ...: ..."), once made.
  std::string reference_choice() const { return job_.chosen(); }
  // The finished reference poll() took, if any.
  const std::optional<reference::ReferenceImage>& reference() const { return reference_; }
  // Takes a finished reference and runs a comparison that is due (a new reference or
  // ground truth, the Compare button) once the frame is drawn at full size. draw() calls
  // it every frame; tests call it directly.
  void poll(renderer::Renderer& r, const LiveState& live);
  // The comparison of the finished reference with the frame, once there is one.
  const std::optional<image::Metrics>& metrics() const { return metrics_; }
  // Why the last reference or comparison failed (empty: it did not).
  const std::string& compare_error() const { return compare_error_; }
  // 0 live, 1 split A/B, 2 reference, 3 error map, 4 ground truth (the radio buttons).
  void set_view(int view, float split = 0.5f) {
    view_ = view;
    split_ = split;
    expand_ = true;  // and show the panel with the metrics
  }
  int view() const { return view_; }

  // What the error map compares (A against B; B is the one nearer the truth) and how.
  enum class Pair { FrameVsReference, FrameVsTruth, ReferenceVsTruth };
  static constexpr int kPairs = 3;
  static std::string pair_name(Pair p);   // "frame vs reference"
  static std::string ratio_name(Pair p);  // "log2(frame/reference)"
  enum class ErrorMap { Absolute, LogRatio };
  // Selects the error view (3) with this map of this pair, and draws it.
  void set_error_map(ErrorMap map, Pair pair = Pair::FrameVsReference);
  ErrorMap error_map() const { return map_; }
  Pair pair() const { return pair_; }
  // The log-ratio map's range in stops (finite, > 0; else ignored).
  void set_log_range(double stops);
  double log_range() const { return log_range_; }

  // One pair's comparison: sss-compare's metrics of the display images (8-bit codes),
  // the log ratio log2(A/B) of the linear images' luminance with its statistics, and
  // the per-pixel values the maps are drawn from.
  struct PairResult {
    image::Metrics metrics;
    image::LogRatioStats log_stats;
    int width = 0, height = 0;
    std::vector<float> errors;       // max_c |a − b| of the display images
    std::vector<float> log2_ratio;   // image::log2_luminance_ratio of the linear images
    std::vector<std::uint8_t> mask;  // 1: geometry in both
    double heat_max = 1.0;           // the absolute map's top
  };
  // Empty until the pair has been compared (or when one of its images is missing).
  const std::optional<PairResult>& result(Pair p) const { return results_[int(p)]; }
  // The error view's image as uploaded: the map of the chosen pair, without its colour
  // bar (the panel draws that), frame size; empty when there is none.
  const image::Image& map_image() const { return map_image_; }

  // The "ground truth" source: an EXR of linear radiance (sss-reference --method
  // random-walk --out, its mean, not its .var.exr) of this view at the window's size.
  // Loading compares it with the frame at the next poll. On failure the previous truth
  // (if any) stays and truth_message() says why, naming the file. Returns success.
  bool load_truth(const std::string& path, const renderer::Renderer& r, const LiveState& live);
  void clear_truth();
  bool has_truth() const { return truth_.has_value(); }
  // "ground truth: PATH (160x90, 535 spp, ...)" or why it did not load / compare.
  const std::string& truth_message() const { return truth_message_; }
  bool truth_error() const { return truth_error_; }
  // A loaded truth whose settings name another built-in scene than the view's (the camera
  // cannot be checked; the scene can): shown in yellow, empty otherwise.
  const std::string& truth_warning() const { return truth_warning_; }

  // A new scene: cancels the reference and forgets the comparison.
  void reset();
  // The Open section's line: a failed open shows in red and opens the Tools window (it
  // starts collapsed), so the user sees why the scene did not change.
  void set_message(std::string message, bool error = false) {
    message_ = std::move(message);
    message_error_ = error;
    if (error) show_open_ = true;
  }
  const std::string& message() const { return message_; }

  // What to blit over the frame: `image` (kDisplayFormat, TRANSFER_SRC_OPTIMAL, frame
  // size) over the columns left of `split` (a fraction of the width; 1 = all of it).
  struct Overlay {
    const vk::Image* image = nullptr;
    float split = 1.0f;
  };
  std::optional<Overlay> overlay() const;

 private:
  void draw_open();
  void draw_compare(renderer::Renderer& r, const LiveState& live);
  void draw_truth(const renderer::Renderer& r, const LiveState& live);
  void draw_metrics();
  void draw_map_controls();
  void draw_export(const renderer::Renderer& r, const LiveState& live);
  // The kernel's material (one of `sss`, the scattering materials), its file path and the
  // kernel and engine buttons; which were pressed.
  struct KernelSaves {
    bool json = false, header = false, hdrp = false, unreal = false;
  };
  KernelSaves draw_kernel_exports(const LiveState& live, const std::vector<int>& sss);
  // Compares every pair whose images are there (frame vs reference only while the
  // reference is of the current view), then draws the chosen map.
  void compare_now(renderer::Renderer& r, const LiveState& live);
  // One pair's test (a) and reference (b) images, display and HDR; null where absent.
  struct PairImages {
    const image::Image *a_display = nullptr, *a_hdr = nullptr, *b_display = nullptr, *b_hdr = nullptr;
  };
  PairImages pair_images(Pair pair, bool reference_current) const;
  // Compares one pair into results_; the error to show ("" when compared).
  std::string compare_one(Pair pair, const PairImages& im);
  void render_map();  // results_[pair_] -> map_image_, heat_image_
  void show_truth(float exposure);  // truth_ -> truth_display_, truth_image_
  vk::Image upload(const image::Image& img, const char* name) const;

  const vk::Context& context_;
  char open_path_[512] = "";
  std::optional<std::string> open_request_;
  std::string message_;
  bool message_error_ = false;
  bool show_open_ = false;  // expand the window (and its Open section) at the next draw

  ReferenceJob job_;
  int estimator_ = int(ReferenceEstimator::Auto);
  float spacing_mfp_ = 0.5f;
  float error_bound_ = 0.3f;
  std::string job_key_;                          // the state the running job renders
  std::optional<reference::ReferenceImage> reference_;
  std::string reference_key_;                    // the state the reference shows
  std::optional<image::Metrics> metrics_;  // frame vs reference
  std::array<std::optional<PairResult>, kPairs> results_;
  Pair pair_ = Pair::FrameVsReference;
  ErrorMap map_ = ErrorMap::Absolute;
  double log_range_ = image::kDefaultLogRange;
  image::Image frame_display_, frame_hdr_;  // the compared frame
  image::Image map_image_;
  vk::Image reference_image_, heat_image_;
  char truth_path_[512] = "";
  std::optional<image::Image> truth_;  // linear, alpha 1 on geometry
  std::string truth_source_;           // the path it was loaded from
  float truth_exposure_ = -1.0f;       // of truth_display_
  image::Image truth_display_;         // tonemapped at the view's exposure, 8-bit codes
  vk::Image truth_image_;
  std::string truth_message_, truth_warning_;
  std::string truth_info_;  // the loaded truth's line (truth_message_ when all is well)
  bool truth_error_ = false;
  bool expand_ = false;  // open the window and the Compare section at the next draw
  int view_ = 0;  // 0 live, 1 split, 2 reference, 3 error map, 4 ground truth
  float split_ = 0.5f;
  std::string compare_error_;
  bool compare_pending_ = false;  // the reference arrived; compare once the frame is full size

  int kernel_material_ = 0;
  char gltf_path_[512] = "";
  char kernel_path_[512] = "";
  bool replace_ = false;
  std::string last_source_;
  std::string export_message_;
};

// The Export section's actions (the buttons call them); each returns "saved PATH" or
// why nothing was written. An existing file is replaced only with `replace`; the scene's
// own files (`inputs`: the glTF and its buffers and images) never are, even with
// `replace`. Files are written atomically.
std::string write_new_file(const std::string& path, const std::string& bytes, bool replace,
                           const std::vector<std::filesystem::path>* inputs = nullptr);
// A glTF/GLB source: a copy with every material's extras.sss (GltfExport.h). A built-in
// scene: {"scene", "materials": [{"name", "extras": {"sss": {...}}}]} as JSON.
std::string export_materials(const LiveState& live, const std::string& path, bool replace);
// The fit and separable kernel the renderer draws `material` with, as the JSON of
// `sss-fit fit --json` or (for a .h path) a C header whose prefix is the file's stem.
std::string export_kernel(const renderer::Renderer& r, const LiveState& live, std::size_t material,
                          const std::string& path, bool replace);

// The material's profile as an engine's asset (profiles/EngineProfiles.h): `hdrp` writes
// BASE.asset and BASE.asset.meta (worldScale the scene's metres per unit), else Unreal's
// BASE-unreal.json and BASE-unreal.py (WorldUnitScale 0.1, Unreal's default). Both files or
// neither; the message ends with the Burley fit's error per channel.
std::string export_engine_profile(const LiveState& live, std::size_t material, const std::string& base,
                                  bool hdrp, bool replace);

// The key of a view for staleness: camera, size, exposure, materials and lights.
std::string live_key(const renderer::Renderer& r, const LiveState& live);

}  // namespace sss::app
