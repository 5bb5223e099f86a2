// sss-viewer's window (DESIGN.md §4: --screenshot FILE after --frames N): under xvfb-run
// when it is installed, with the validation layer (synchronization checks included) and
// no message allowed. Without a display the viewer says so and exits 1.
#include <gtest/gtest.h>

#include "image/Image.h"

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

// The largest difference in 8-bit codes between two PNGs of the same size (256: sizes
// differ or unreadable).
float max_code_difference(const std::string& a_path, const std::string& b_path) {
  const sss::image::Image a = read_png(a_path), b = read_png(b_path);
  if (a.width == 0 || a.width != b.width || a.height != b.height) return 256.0f;
  float d = 0.0f;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) d = std::max(d, std::fabs(a.rgba[i] - b.rgba[i]));
  return d * 255.0f;
}

// The headless frame of `scene_args` at w x h (validation on), as a PNG path, with the
// window's default anti-aliasing and background (--aa auto and --background auto are fxaa
// and grey in the window, off and none headless).
std::string headless_png(const std::string& scene_args, int w, int h) {
  const std::string png = temp_path("headless_" + std::to_string(w) + "x" + std::to_string(h) + ".png");
  const CommandRun r = run_shell("SSS_VALIDATION=1 " + std::string(SSS_VIEWER_EXE) + " " + scene_args +
                                 " --headless --aa fxaa --background 0.22 --width " + std::to_string(w) +
                                 " --height " + std::to_string(h) + " --out " + png);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(has_validation_message(r.out)) << r.out;
  return png;
}

TEST(ViewerWindow, ScreenshotMatchesTheHeadlessFrame) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::string window_png = temp_path("window.png"), headless_png = temp_path("headless.png");
  std::filesystem::remove(window_png);
  // The window anti-aliases and draws a grey background by default (--aa auto,
  // --background auto: kWindowBackground), so the headless frame asks for both.
  const CommandRun w = run_windowed("builtin:sphere --width 320 --height 180 --frames 5 --screenshot " +
                             window_png);
  ASSERT_EQ(w.code, 0) << w.out;
  EXPECT_FALSE(has_validation_message(w.out)) << w.out;
  const CommandRun h = run_shell("SSS_VALIDATION=1 " + std::string(SSS_VIEWER_EXE) +
                            " builtin:sphere --headless --aa fxaa --background 0.22 --width 320 --height 180 --out " +
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
    // After the resize, the minimize (a real iconify and two 0x0 framebuffers) and the
    // restore, the frame is the headless one of the final size (to one 8-bit code, as in
    // ScreenshotMatchesTheHeadlessFrame).
    EXPECT_LE(max_code_difference(png, headless_png("builtin:sphere --mode gaussians", 160, 90)), 1.0f)
        << vsync;
  }
  std::filesystem::remove(png);
}

// A resize storm: 50 size changes over ~17 frames, two before a frame reads its size and
// one between rendering and acquiring (the swapchain goes out of date under the frame),
// 1x1, thin (1x400, 900x1) and larger than the 1280x720 screen (2000x1200), then back to
// 200x120. The viewer keeps going, the validation layer (synchronization checks on)
// says nothing, and the frames after the storm are the headless frame of the final size.
TEST(ViewerWindow, ResizeStormEndsWithTheRightFrame) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::string png = temp_path("storm.png");
  std::filesystem::remove(png);
  const CommandRun r = run_windowed("builtin:sphere --width 200 --height 120 --frames 3 --vsync off "
                                    "--test-resize-storm --stats --screenshot " + png);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(has_validation_message(r.out)) << r.out;
  EXPECT_NE(r.out.find("window 200x120 (rendered 200x120)"), std::string::npos) << r.out;
  const sss::image::Image image = read_png(png);
  EXPECT_EQ(image.width, 200);
  EXPECT_EQ(image.height, 120);
  EXPECT_LE(max_code_difference(png, headless_png("builtin:sphere", 200, 120)), 1.0f);
  std::filesystem::remove(png);
}

// The number after `row` in --stats output (-1 if absent).
long long stat(const std::string& out, const std::string& row) {
  const auto at = out.find("\n" + row + " ");
  if (at == std::string::npos) return -1;
  return std::atoll(out.c_str() + at + 1 + row.size());
}

// No report of a sanitizer or a crash: the run ended through main's error path.
void expect_clean_failure(const CommandRun& r, const std::string& output, const std::string& what) {
  EXPECT_EQ(r.code, 1) << what << "\n" << r.out;
  EXPECT_NE(r.out.find("sss-viewer: error: "), std::string::npos) << what << "\n" << r.out;
  EXPECT_EQ(r.out.find("AddressSanitizer"), std::string::npos) << what << "\n" << r.out;
  EXPECT_EQ(r.out.find("runtime error:"), std::string::npos) << what << "\n" << r.out;
  EXPECT_FALSE(has_validation_message(r.out)) << what << "\n" << r.out;
  EXPECT_FALSE(std::filesystem::exists(output)) << what;  // no half-written image
}

// A device-memory allocation that fails (simulated: SSS_FAIL_ALLOCATION_AFTER=N makes
// every allocation after the first N fail as VK_ERROR_OUT_OF_DEVICE_MEMORY) while
// starting, headless and in the window: a clear error naming the simulated failure,
// exit 1, no output file.
TEST(ViewerFaults, AllocationFailureAtStartIsReportedAndExitsCleanly) {
  const std::string png = temp_path("oom.png");
  for (int n : {0, 1, 4, 12}) {
    std::filesystem::remove(png);
    const CommandRun h = run_shell("SSS_VALIDATION=1 SSS_FAIL_ALLOCATION_AFTER=" + std::to_string(n) +
                                   " " + SSS_VIEWER_EXE + " builtin:sphere --headless --width 64"
                                   " --height 36 --out " + png);
    expect_clean_failure(h, png, "headless N=" + std::to_string(n));
    EXPECT_NE(h.out.find("simulated allocation failure"), std::string::npos) << h.out;
    if (!have_xvfb()) continue;
    const CommandRun w = sss::testing::run_windowed_own_status(
        "builtin:sphere --width 64 --height 36 --frames 2 --screenshot " + png,
        "SSS_FAIL_ALLOCATION_AFTER=" + std::to_string(n));
    expect_clean_failure(w, png, "window N=" + std::to_string(n));
    EXPECT_NE(w.out.find("simulated allocation failure"), std::string::npos) << w.out;
  }
}

// The same failure in the middle of a session, after the first frame: during a resize
// storm, and while opening another file (at frame 2). The counts come from a run
// without a limit (--stats: allocations at the first frame and at the end). A failed
// open keeps the scene shown and says why (as a bad file does); every later allocation
// fails too, so the screenshot's read-back then ends the run with exit 1.
TEST(ViewerFaults, AllocationFailureMidSessionIsReportedAndExitsCleanly) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::string png = temp_path("oom_mid.png");
  const std::string tile = std::string(SSS_SOURCE_DIR) + "/assets/textured_tile.glb";
  for (const std::string& test : {std::string("--test-resize-storm"), "--test-open " + tile}) {
    const std::string args = "builtin:sphere --width 64 --height 36 --frames 4 --stats " + test +
                             " --screenshot " + png;
    const CommandRun full = sss::testing::run_windowed_own_status(args);
    ASSERT_EQ(full.code, 0) << full.out;
    const bool open = test != "--test-resize-storm";
    if (open) {
      ASSERT_NE(full.out.find("opened " + tile), std::string::npos) << full.out;
    }
    const long long first = stat(full.out, "allocations @1"), total = stat(full.out, "allocations");
    ASSERT_GT(first, 0) << full.out;
    ASSERT_GT(total, first) << test << " allocates after the first frame\n" << full.out;
    std::filesystem::remove(png);
    const long long n = first + (total - first) / 2;  // fails after the first frame
    const CommandRun w = sss::testing::run_windowed_own_status(
        args, "SSS_FAIL_ALLOCATION_AFTER=" + std::to_string(n));
    expect_clean_failure(w, png, test + " N=" + std::to_string(n));
    EXPECT_NE(w.out.find("simulated allocation failure"), std::string::npos) << w.out;
    if (open) {
      EXPECT_NE(w.out.find("sss-viewer: error: " + tile + ": simulated allocation failure"),
                std::string::npos) << w.out;
    }
  }
  std::filesystem::remove(png);
}

// Host memory exhausted: std::bad_alloc thrown (hidden --test-host-oom) after the scene
// loaded, and inside the window's frame loop at frame 2 (the frame in flight must finish
// before unwinding destroys what it uses) or headless after the first frame: main says
// so and exits 1, no image is written, the validation layer says nothing.
TEST(ViewerFaults, HostOutOfMemoryIsReportedAndExitsCleanly) {
  const std::string png = temp_path("host_oom.png");
  for (const char* stage : {"load", "frame"}) {
    std::filesystem::remove(png);
    const CommandRun h = run_shell("SSS_VALIDATION=1 " + std::string(SSS_VIEWER_EXE) +
                                   " builtin:sphere --headless --width 64 --height 36 --test-host-oom " +
                                   stage + " --out " + png);
    expect_clean_failure(h, png, std::string("headless ") + stage);
    EXPECT_NE(h.out.find("sss-viewer: error: out of host memory"), std::string::npos) << h.out;
    if (!have_xvfb()) continue;
    const CommandRun w = sss::testing::run_windowed_own_status(
        std::string("builtin:sphere --width 64 --height 36 --frames 4 --test-host-oom ") + stage +
        " --screenshot " + png);
    expect_clean_failure(w, png, std::string("window ") + stage);
    EXPECT_NE(w.out.find("sss-viewer: error: out of host memory"), std::string::npos) << w.out;
  }
}

// The address space capped at 256 MiB (ulimit -v): the scene loads, the Vulkan driver
// runs out of host memory; a clear error and exit 1, not a crash. Skipped under
// AddressSanitizer, whose shadow memory needs terabytes of address space.
TEST(ViewerFaults, AddressSpaceLimitIsReportedAndExitsCleanly) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ulimit -v cannot be used with AddressSanitizer";
#else
  const std::string png = temp_path("ulimit.png");
  std::filesystem::remove(png);
  const CommandRun h = run_shell("ulimit -v 262144; " + std::string(SSS_VIEWER_EXE) +
                                 " builtin:sphere --headless --width 64 --height 36 --out " + png);
  expect_clean_failure(h, png, "ulimit -v");
#endif
}

TEST(ViewerWindow, ExrScreenshotAndStats) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const std::string exr = temp_path("shot.exr");
  std::filesystem::remove(exr);
  const CommandRun r = run_windowed("builtin:sphere --width 96 --height 54 --frames 3 --stats --screenshot " + exr);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(has_validation_message(r.out)) << r.out;
  for (const char* row : {"window 96x54", "shadow", "composite", "fps", "frame targets"})
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
