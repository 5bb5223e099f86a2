// sss-viewer's window (DESIGN.md §4: --screenshot FILE after --frames N): under xvfb-run
// when it is installed, with the validation layer (synchronization checks included) and
// no message allowed. Without a display the viewer says so and exits 1.
#include <gtest/gtest.h>

#include "renderer/image/Image.h"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "ViewerRun.h"

#ifdef SSS_VIEWER_EXE

namespace {

using CommandRun = sss::testing::CliRun;
using sss::testing::has_validation_message;
using sss::testing::have_xvfb;
using sss::testing::read_png;
using sss::testing::run_shell;
using sss::testing::run_windowed;

std::string temp_path(const std::string& name) {
  return sss::testing::viewer_temp_path("viewer_window_test", name);
}

TEST(ViewerWindow, ScreenshotMatchesTheHeadlessFrame) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::string window_png = temp_path("window.png"), headless_png = temp_path("headless.png");
  std::filesystem::remove(window_png);
  const CommandRun w = run_windowed("builtin:sphere --width 320 --height 180 --frames 5 --screenshot " +
                             window_png);
  ASSERT_EQ(w.code, 0) << w.out;
  EXPECT_FALSE(has_validation_message(w.out)) << w.out;
  const CommandRun h = run_shell("SSS_VALIDATION=1 " + std::string(SSS_VIEWER_EXE) +
                            " builtin:sphere --headless --width 320 --height 180 --out " +
                            headless_png);
  ASSERT_EQ(h.code, 0) << h.out;
  EXPECT_FALSE(has_validation_message(h.out)) << h.out;

  const sss::image::Image a = read_png(window_png), b = read_png(headless_png);
  ASSERT_EQ(a.width, 320);
  ASSERT_EQ(a.height, 180);
  ASSERT_EQ(b.width, a.width);
  ASSERT_EQ(b.height, a.height);
  // Not blank: the sphere covers part of the frame, with more than one colour.
  float lo = 1.0f, hi = 0.0f;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
    lo = std::min(lo, a.rgba[i + 1]);
    hi = std::max(hi, a.rgba[i + 1]);
  }
  EXPECT_GT(hi - lo, 0.2f);
  // The same Renderer draws the same view at the same size, so the frames are equal
  // (bit for bit on lavapipe): allow one 8-bit code for a device whose float results
  // depend on submission timing.
  float max_diff = 0.0f;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    max_diff = std::max(max_diff, std::fabs(a.rgba[i] - b.rgba[i]));
  EXPECT_LE(max_diff, 1.0f / 255.0f + 1e-6f);
  std::filesystem::remove(window_png);
  std::filesystem::remove(headless_png);
}

TEST(ViewerWindow, ResizeAndMinimizeWhileRendering) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::string png = temp_path("resize.png");
  for (const char* vsync : {"on", "off"}) {
    std::filesystem::remove(png);
    const CommandRun r = run_windowed(std::string("builtin:sphere --width 160 --height 90 --frames 10 --test-resize"
                                           " --mode gaussians --vsync ") + vsync + " --screenshot " + png);
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_FALSE(has_validation_message(r.out)) << r.out;
    const sss::image::Image image = read_png(png);
    EXPECT_GT(image.width, 0) << vsync;
  }
  std::filesystem::remove(png);
}

TEST(ViewerWindow, ExrScreenshotAndStats) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::string exr = temp_path("shot.exr");
  std::filesystem::remove(exr);
  const CommandRun r = run_windowed("builtin:sphere --width 96 --height 54 --frames 3 --stats --screenshot " + exr);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(has_validation_message(r.out)) << r.out;
  for (const char* row : {"window 96x54", "shadow", "composite", "fps"})
    EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
  auto image = sss::image::read_image(exr);
  ASSERT_TRUE(std::holds_alternative<sss::image::Image>(image)) << exr;
  std::filesystem::remove(exr);
}

TEST(ViewerWindow, NoDisplayIsARuntimeError) {
  const std::string png = temp_path("nodisplay.png");
  const CommandRun r = run_shell("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(SSS_VIEWER_EXE) +
                            " builtin:sphere --frames 1 --screenshot " + png);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("sss-viewer: error: no display available; use --headless --out "
                          "FILE.png to render without a window"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(std::filesystem::exists(png));
}

}  // namespace

#endif  // SSS_VIEWER_EXE
