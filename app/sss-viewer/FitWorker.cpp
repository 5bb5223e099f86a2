#include "FitWorker.h"

#include <exception>
#include <utility>

namespace sss::app {

void FitWorker::compute_default(FitRequest& request, FitResult& result) {
  for (std::size_t i = 0; i < request.specs.size() && i < request.materials.size(); ++i) {
    if (!request.specs[i]) continue;
    const SssSpec& s = *request.specs[i];
    if (!s.enabled) {
      request.materials[i].sss.enabled = false;
      continue;
    }
    auto made = s.layers.empty()
                    ? scene::make_sss_material(s.source, s.model, s.gaussians, s.scale, s.albedo_mode)
                    : scene::make_layered_sss_material(s.layers, s.gaussians, s.scale, s.albedo_mode);
    if (auto* e = std::get_if<FieldError>(&made)) {
      result.error = e->what();
      result.error_material = static_cast<int>(i);
      return;
    }
    request.materials[i].sss = std::get<scene::SssMaterial>(std::move(made));
  }
  const std::size_t n = request.materials.size();
  std::vector<bool> reuse(n, false);
  if (request.previous)
    for (std::size_t i = 0; i < n; ++i) reuse[i] = i >= request.specs.size() || !request.specs[i];
  result.data = request.previous ? renderer::build_material_data(request.materials,
                                                                 request.separable_taps,
                                                                 *request.previous, reuse,
                                                                 request.single_scattering)
                                 : renderer::build_material_data(request.materials,
                                                                 request.separable_taps,
                                                                 request.single_scattering);
  const bool reused = request.previous && request.previous->separable_taps == request.separable_taps &&
                      request.previous->single_scattering == request.single_scattering;
  result.plots.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    if (request.materials[i].sss.enabled && result.data.profiles[i] && !(reused && reuse[i]))
      result.plots[i] = make_profile_plot(request.materials[i].sss, result.data.profiles[i]->fit);
}

FitWorker::FitWorker(Compute compute) : compute_(std::move(compute)), thread_([this] { run(); }) {}

FitWorker::~FitWorker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    queued_.reset();
  }
  wake_.notify_all();
  thread_.join();
}

std::uint64_t FitWorker::submit(FitRequest request) {
  std::uint64_t id = 0;
  {
    std::lock_guard lock(mutex_);
    id = next_id_++;
    if (queued_) ++dropped_;  // never computed
    queued_.emplace(id, std::move(request));
    latest_ = id;
    if (ready_) {  // finished but not taken: stale now
      ready_.reset();
      ++dropped_;
    }
  }
  wake_.notify_all();
  return id;
}

std::optional<FitResult> FitWorker::take() {
  std::lock_guard lock(mutex_);
  std::optional<FitResult> out = std::move(ready_);
  ready_.reset();
  if (out) done_.notify_all();
  return out;
}

bool FitWorker::busy() const {
  std::lock_guard lock(mutex_);
  return queued_.has_value() || running_ != 0 || ready_.has_value();
}

bool FitWorker::wait_idle(std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  // Idle for a waiter: nothing queued or running (a ready result is for take()).
  return done_.wait_for(lock, timeout, [this] { return !queued_ && running_ == 0; });
}

std::uint64_t FitWorker::latest() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

std::uint64_t FitWorker::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

void FitWorker::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || queued_.has_value(); });
    if (stop_) return;
    auto [id, request] = std::move(*queued_);
    queued_.reset();
    running_ = id;
    lock.unlock();

    FitResult result;
    result.id = id;
    const auto start = Clock::now();
    try {
      compute_(request, result);
    } catch (const std::exception& e) {
      result.error = e.what();
    }
    if (!result.error.empty()) {
      result.data = {};
      result.plots.clear();
    }
    result.fit_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    result.request = std::move(request);

    lock.lock();
    running_ = 0;
    if (id == latest_)
      ready_ = std::move(result);
    else
      ++dropped_;  // a newer request was submitted while this one ran
    done_.notify_all();
  }
}

}  // namespace sss::app
