// FitWorker: the viewer's material refits off the render thread. The UI submits the
// whole material list after each edit; one worker thread runs build_material_data (the
// Gaussian fit and separable kernel, pure CPU) plus the profile plots and hands back the
// result, which the render thread only uploads (Renderer::set_materials(materials, data)).
//
// Newest edit wins: a request submitted while another waits replaces it (the older one
// is never computed), and a result finished after a newer request was submitted is
// dropped, so take() only ever returns the result of the latest request. Both count in
// dropped().
#pragma once

#include "ProfilePlot.h"

#include "renderer/MaterialTable.h"
#include "scene/Material.h"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace sss::app {

using Clock = std::chrono::steady_clock;

// An SSS material as the editor describes it, resolved on the worker (an artist colour
// under pbd inverts the model's total reflectance: tens of ms).
struct SssSpec {
  // false: the material becomes an opaque PBR surface again (the viewer's "enable
  // subsurface" switch); its last medium stays in SssMaterial, disabled, and the other
  // fields are not used.
  bool enabled = true;
  scene::SssSource source;
  profiles::Model model = profiles::kDefaultModel;
  int gaussians = scene::kDefaultGaussians;
  double scale = 1.0;
  scene::AlbedoMode albedo_mode = scene::AlbedoMode::PostScatter;
  // Non-empty: a layered material (scene::make_layered_sss_material); `source` and `model`
  // are then not used.
  profiles::LayerStack layers;
};

struct FitRequest {
  std::vector<scene::Material> materials;
  // specs[i] set: material i's sss becomes make_sss_material(spec) (a FieldError fails
  // the request, naming the field, in FitResult::error with error_material = i).
  std::vector<std::optional<SssSpec>> specs;
  int separable_taps = 17;
  // RenderOptions::single_scattering: profiles without their once-scattered light.
  bool single_scattering = renderer::RenderOptions{}.single_scattering;
  Clock::time_point edited{};  // when the user made the edit (latency measurement)
  // The data the renderer draws `materials` with: the materials without a spec keep
  // their fits from it (and get no new plot) instead of being refitted. Null: all.
  std::shared_ptr<const renderer::MaterialData> previous;
};

struct FitResult {
  std::uint64_t id = 0;
  FitRequest request;
  renderer::MaterialData data;                    // empty when `error` is set
  std::vector<std::optional<ProfilePlot>> plots;  // per refitted SSS material
  std::string error;   // a spec did not resolve, or build_material_data threw
  int error_material = -1;  // the material whose spec failed; -1: not one material
  double fit_ms = 0.0;                            // the worker's time for this request
};

class FitWorker {
 public:
  // The work for one request: the default resolves the specs into request.materials,
  // then builds MaterialData and the plots. Tests pass
  // a function that blocks to control the timing.
  using Compute = std::function<void(FitRequest&, FitResult&)>;
  static void compute_default(FitRequest& request, FitResult& result);

  explicit FitWorker(Compute compute = compute_default);
  ~FitWorker();  // waits for the running request, discards the rest
  FitWorker(const FitWorker&) = delete;
  FitWorker& operator=(const FitWorker&) = delete;

  // Queues `request` (replacing a queued one) and returns its id (1, 2, ...).
  std::uint64_t submit(FitRequest request);
  // The latest request's result, once, if it has finished.
  std::optional<FitResult> take();
  // A request is queued or running whose result take() has not returned yet.
  bool busy() const;
  // Blocks until !busy() or `timeout`; true if idle.
  bool wait_idle(std::chrono::milliseconds timeout) const;
  std::uint64_t latest() const;
  std::uint64_t dropped() const;

 private:
  void run();

  Compute compute_;
  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;  // the worker: a request or stop
  mutable std::condition_variable done_;  // waiters: a result or a drop
  std::optional<std::pair<std::uint64_t, FitRequest>> queued_;
  std::optional<FitResult> ready_;
  std::uint64_t next_id_ = 1, latest_ = 0, running_ = 0, dropped_ = 0;
  bool stop_ = false;
  std::thread thread_;  // last: started after the state above exists
};

}  // namespace sss::app
