// What the tests of sss-viewer's window share: running it under xvfb-run (a virtual X
// server; lavapipe renders) with the validation layer and synchronization checks on,
// spotting a validation message in its output, and reading the PNGs it writes.
#pragma once

#include "common/CliRun.h"

#include "image/Image.h"

#include <cstdlib>
#include <filesystem>
#include <string>

namespace sss::testing {

inline bool have_xvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

#ifdef SSS_VIEWER_EXE
// `sss-viewer ARGS` in a 1280x720 virtual screen, SSS_VALIDATION=1 and `env` (more
// VAR=VALUE settings) in its environment.
inline CliRun run_windowed(const std::string& args, const std::string& env = "") {
  return run_shell("SSS_VALIDATION=1 " + env + " xvfb-run -a -s \"-screen 0 1280x720x24\" " +
                   std::string(SSS_VIEWER_EXE) + " " + args);
}

// As run_windowed, but `code` is sss-viewer's own exit status, not xvfb-run's (which
// can fail on its own, e.g. "problem while cleaning up temporary directory", exit 5,
// seen once with other X servers starting beside it). -1: the marker is missing.
inline CliRun run_windowed_own_status(const std::string& args, const std::string& env = "") {
  CliRun r = run_shell("SSS_VALIDATION=1 " + env + " xvfb-run -a -s \"-screen 0 1280x720x24\" sh -c '" +
                       std::string(SSS_VIEWER_EXE) + " " + args + "; echo sss-viewer-exit=$?'");
  const auto at = r.out.rfind("sss-viewer-exit=");
  r.code = at == std::string::npos ? -1 : std::atoi(r.out.c_str() + at + 16);
  return r;
}
#endif

// A path in the temporary folder, unique to one test file by `prefix`.
inline std::string viewer_temp_path(const std::string& prefix, const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("sss_" + prefix + "_" + name)).string();
}

// Any message of the validation layer (or the note that it was asked for but missing).
inline bool has_validation_message(const std::string& output) {
  return output.find("[vulkan validation") != std::string::npos ||
         output.find("[vulkan performance") != std::string::npos ||
         output.find("validation requested but") != std::string::npos;
}

// The PNG at `path`, or an empty image when it cannot be read.
inline image::Image read_png(const std::string& path) {
  auto image = image::read_image(path);
  if (!std::holds_alternative<image::Image>(image)) return {};
  return std::get<image::Image>(std::move(image));
}

}  // namespace sss::testing
