// ReferenceJob: the CPU reference of one view on a worker thread (Tools.h).
#include "Tools.h"

#include "reference/ReferenceRenderer.h"

#include <exception>
#include <mutex>
#include <string>
#include <utility>

namespace sss::app {

void ReferenceJob::start(scene::Scene scene, const reference::ReferenceOptions& options, bool choose) {
  cancel();
  {
    std::lock_guard lock(mutex_);
    stage_ = choose ? "choosing" : "starting";
    fraction_ = 0.0;
    result_.reset();
    error_.clear();
    chosen_.clear();
  }
  cancel_ = false;
  running_ = true;
  worker_ = std::thread([this, s = std::move(scene), options, choose] {
    try {
      reference::ReferenceOptions o = options;
      if (choose) {
        const reference::EstimatorChoice choice = reference::choose_estimator(s, o);
        o = reference::with_choice(o, choice);
        std::lock_guard lock(mutex_);
        chosen_ = reference::describe(choice, options.spacing_mfp);
      }
      if (cancel_) throw reference::Cancelled();
      reference::ReferenceImage img = reference::render_reference(
          s, o,
          [this](const char* stage, double f) {
            std::lock_guard lock(mutex_);
            stage_ = stage;
            fraction_ = f;
          },
          &cancel_);
      std::lock_guard lock(mutex_);
      result_ = std::move(img);
    } catch (const reference::Cancelled&) {
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      error_ = e.what();
    }
    running_ = false;
  });
}

void ReferenceJob::cancel() {
  cancel_ = true;
  if (worker_.joinable()) worker_.join();
  running_ = false;
}

std::string ReferenceJob::progress() const {
  std::lock_guard lock(mutex_);
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s %.0f%%", stage_.c_str(), 100.0 * fraction_);
  return buf;
}

double ReferenceJob::fraction() const {
  std::lock_guard lock(mutex_);
  return fraction_;
}

std::optional<reference::ReferenceImage> ReferenceJob::take() {
  std::lock_guard lock(mutex_);
  if (!result_) return std::nullopt;
  std::optional<reference::ReferenceImage> out = std::move(result_);
  result_.reset();
  return out;
}

std::string ReferenceJob::chosen() const {
  std::lock_guard lock(mutex_);
  return chosen_;
}

std::string ReferenceJob::take_error() {
  std::lock_guard lock(mutex_);
  std::string e = std::move(error_);
  error_.clear();
  return e;
}

// ---- ViewerTools -----------------------------------------------------------------

}  // namespace sss::app
