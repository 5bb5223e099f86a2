#include "CommandSupport.h"

#include "renderer/image/AtomicFile.h"

#include <cstdio>
#include <iostream>
#include <mutex>

#include <unistd.h>

namespace sss::app {

int usage_error(const FieldError& e) { return usage_error(e.what()); }

int usage_error(const std::string& message) {
  std::cerr << "sss-fit: error: " << message << '\n';
  return kExitUsage;
}

profiles::ModelOptions model_options(const CommonArgs& a) {
  profiles::ModelOptions o;
  if (a.pbd_samples > 0) o.pbd_samples = a.pbd_samples;
  o.mc_photons = a.photons;
  o.mc_seed = a.seed;
  o.mc_threads = a.threads;
  return o;
}

std::optional<profiles::Model> resolve_model(const std::string& name) {
  auto m = profiles::parse_model(name);
  if (!m) usage_error("--model: unknown model '" + name + "'; known: " + profiles::model_names());
  return m;
}

nlohmann::json to_json(const Rgb& v) { return nlohmann::json::array({v[0], v[1], v[2]}); }

bool write_output(const std::string& path, const std::string& bytes) {
  try {
    image::write_file_atomically(path, bytes);
    return true;
  } catch (const image::WriteError& e) {
    std::cerr << "sss-fit: error: " << e.what() << '\n';
    return false;
  }
}

void progress_bar(const char* what, double fraction) {
  static const bool tty = ::isatty(STDERR_FILENO) != 0;
  if (!tty) return;
  static std::mutex mutex;
  static int last = -1;
  std::lock_guard lock(mutex);
  const int pct = static_cast<int>(fraction * 100.0 + 0.5);
  if (pct == last) return;
  last = pct;
  const int filled = pct * 30 / 100;
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", what, filled, "==============================",
               30 - filled, "", pct);
  if (pct >= 100) {
    std::fputc('\n', stderr);
    last = -1;
  }
  std::fflush(stderr);
}

}  // namespace sss::app
