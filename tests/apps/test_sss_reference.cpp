// sss-reference's documented commands and errors (DESIGN.md §4): exit 0 with the file
// written, 2 for bad usage or input naming the option or file, 130 when interrupted,
// and never a partial output file.
#ifdef SSS_REFERENCE_EXE

#include "common/CliRun.h"
#include "common/FrameLessHighlight.h"
#include "image/Image.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using sss::testing::CliRun;
using sss::testing::slurp;

fs::path scratch() {
  static const fs::path dir = sss::testing::scratch_dir("sss-reference-test");
  return dir;
}

CliRun reference(const std::string& args) {
  return sss::testing::run_cli(SSS_REFERENCE_EXE, args, scratch() / "stderr.txt");
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

TEST(SssReferenceApp, HelpListsTheOptions) {
  const CliRun r = reference("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* opt : {"--out", "--width", "--model", "--spacing", "--error-bound", "--brute-force",
                          "--threads", "--diffuse-only", "--preset"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(SssReferenceApp, RendersExrAndPng) {
  const fs::path exr = scratch() / "sphere.exr", png = scratch() / "sphere.png";
  const CliRun r = reference("builtin:sphere --out " + exr.string() + " --png " + png.string() +
                          " --width 32 --height 18 --spacing 2 --stats");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(starts_with(slurp(exr), "\x76\x2f\x31\x01"));  // OpenEXR magic
  EXPECT_TRUE(starts_with(slurp(png), "\x89PNG"));
  EXPECT_NE(r.err.find("irradiance points"), std::string::npos);  // --stats
  EXPECT_NE(r.err.find("render done"), std::string::npos);        // progress (not a tty)
}

// --no-specular: the same render less its specular term (the same points: same seed).
// --estimator auto, the default: it says what it chose and why, and the render is the
// chosen estimator's (ChooseEstimator.* checks the choice itself against closed forms).
// builtin:edge at 0.1 mm pixels: points that dense would exceed the cap, so the probe (its
// frame carries the Monte Carlo attributes); the bunny at 320x180 (pixels of ~1.2 mm
// against points 1.34 mm apart): the octree with points as dense as the pixels; options
// of one estimator pick it without a note.
TEST(SssReferenceApp, AutoEstimatorSaysWhatItChoseAndRendersWithIt) {
  const fs::path edge = scratch() / "auto-edge.exr", bunny = scratch() / "auto-bunny.exr";
  const CliRun e = reference("builtin:edge --width 400 --height 1 --diffuse-only --out " + edge.string());
  ASSERT_EQ(e.code, 0) << e.err;
  EXPECT_NE(e.err.find("--estimator auto chose probe (24 batches per pixel)"), std::string::npos) << e.err;
  EXPECT_NE(e.err.find("would exceed --max-points"), std::string::npos) << e.err;
  auto image = sss::image::read_image(edge.string());
  ASSERT_TRUE(std::holds_alternative<sss::image::Image>(image));
  bool probe_attributes = false;
  for (const auto& [key, value] : std::get<sss::image::Image>(image).attributes)
    if (key == "sssSpp" && value == "24") probe_attributes = true;
  EXPECT_TRUE(probe_attributes) << "the frame is not the probe's";

  const CliRun b = reference("builtin:bunny --width 320 --height 180 --stats --out " + bunny.string());
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NE(b.err.find("--estimator auto chose octree at spacing 0."), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("irradiance points"), std::string::npos) << "not the octree's stats: " << b.err;

  const CliRun o = reference("builtin:edge --width 400 --height 1 --spacing 2 --out " + edge.string());
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err.find("--estimator auto chose"), std::string::npos) << o.err;
  // --transmission (ReferenceTransmission.* checks what it does) belongs to the octree.
  const CliRun t = reference("builtin:sphere --width 16 --height 9 --transmission local --stats --out " + bunny.string());
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_EQ(t.err.find("--estimator auto chose"), std::string::npos) << t.err;
  EXPECT_NE(t.err.find("irradiance points"), std::string::npos) << "not the octree's stats: " << t.err;
  // So does --thickness (ShadowMaps.Thickness* checks what it reads), with its map's size.
  const CliRun m = reference("builtin:sphere --width 16 --height 9 --transmission local --thickness-from shadow-map "
                             "--shadow-map-size 256 --stats --out " + bunny.string());
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(m.err.find("--estimator auto chose"), std::string::npos) << m.err;
  EXPECT_NE(m.err.find("irradiance points"), std::string::npos) << "not the octree's stats: " << m.err;
  const CliRun q = reference("builtin:bunny --width 16 --height 9 --quiet --out " + bunny.string());
  ASSERT_EQ(q.code, 0) << q.err;
  EXPECT_EQ(q.err.find("note"), std::string::npos) << "--quiet prints no note: " << q.err;
}

TEST(SssReferenceApp, NoSpecularIsTheFrameLessItsHighlight) {
  const fs::path whole = scratch() / "whole.exr", scattered = scratch() / "scattered.exr";
  const std::string args = "builtin:sphere --width 48 --height 27 --spacing 2 --quiet --out ";
  ASSERT_EQ(reference(args + whole.string()).code, 0);
  const CliRun r = reference(args + scattered.string() + " --no-specular");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto a = sss::image::read_image(whole.string()), b = sss::image::read_image(scattered.string());
  ASSERT_TRUE(std::holds_alternative<sss::image::Image>(a) && std::holds_alternative<sss::image::Image>(b));
  const auto h = sss::testing::check_frame_less_highlight(std::get<sss::image::Image>(a),
                                                          std::get<sss::image::Image>(b));
  EXPECT_GT(h.largest_drop, 0.01) << "no pixel lost a highlight";
}

TEST(SssReferenceApp, MaterialOptionsOverrideTheScene) {
  const fs::path exr = scratch() / "marble.exr";
  const CliRun r = reference("builtin:sphere --out " + exr.string() +
                          " --width 16 --height 9 --spacing 2 --preset marble --model pbd --quiet");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // --quiet: no progress
}

TEST(SssReferenceApp, BadInputExitsTwoNamingTheProblem) {
  const fs::path out = scratch() / "bad.exr";
  struct Case {
    std::string args, expect;
  };
  const Case cases[] = {
      {"builtin:sphere", "--out"},
      {"builtin:sphere --out " + out.string() + " --width 0", "--width"},
      {"builtin:sphere --out " + (scratch() / "x.jpg").string(), "--out"},
      {"builtin:nope --out " + out.string(), "builtin:nope"},
      {(scratch() / "missing.glb").string() + " --out " + out.string(), "missing.glb"},
      {"builtin:sphere --out " + out.string() + " --model magic", "--model"},
      {"builtin:sphere --out " + out.string() + " --sigma-a -1 --sigma-s 1", "--sigma-a"},
      {"builtin:sphere --out " + out.string() + " --spacing 0", "spacing"},
      {"builtin:sphere --out " + out.string() + " --spacing 0.5 --max-points 10", "exceed"},
      {"builtin:sphere --out " + out.string() + " --error-bound -1", "--error-bound"},
      // The GPU's sky occlusion belongs to the GPU-shadow mode; ray-traced shadows sample it.
      {"builtin:sphere --out " + out.string() + " --sky-occlusion off", "--sky-occlusion"},
      {"builtin:sphere --out " + out.string() + " --shadows shadow-map --sky-occlusion maybe", "--sky-occlusion"},
  };
  for (const Case& c : cases) {
    const CliRun r = reference(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST(SssReferenceApp, UnwritableOutputIsARuntimeFailure) {
  const CliRun r = reference("builtin:sphere --out /nonexistent-dir/x.exr --width 8 --height 8 --spacing 3 --quiet");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("/nonexistent-dir/x.exr"), std::string::npos) << r.err;
  // A "folder" that is a regular file (refused even when running as root), for --png too.
  const fs::path file = scratch() / "a-file";
  { std::ofstream(file) << "x"; }
  const CliRun p = reference("builtin:sphere --out " + (scratch() / "ok.exr").string() + " --png " +
                             (file / "x.png").string() + " --width 8 --height 8 --spacing 3 --quiet");
  EXPECT_EQ(p.code, 1) << p.err;
  EXPECT_NE(p.err.find((file / "x.png").string()), std::string::npos) << p.err;
  EXPECT_FALSE(fs::exists(scratch() / "ok.exr"));  // refused before anything was written
}

// Starts a render long enough to interrupt (builtin:sphere at 0.25 mfp, 640x360, one
// thread) into `out`, sends `sig` 1.5 s later and returns the wait status (-1 if the
// process could not be started or waited for).
int render_and_signal(const fs::path& out, int sig) {
  const std::string exe = SSS_REFERENCE_EXE;
  std::vector<std::string> args = {exe, "builtin:sphere", "--out", out.string(), "--spacing", "0.25", "--quiet", "--threads", "1"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ::kill(pid, sig);
  int status = 0;
  return ::waitpid(pid, &status, 0) == pid ? status : -1;
}

TEST(SssReferenceApp, CtrlCStopsWithoutWritingAFile) {
  // A render long enough to interrupt (builtin:sphere at 0.25 mfp, 640x360); SIGINT
  // after the process has started. Exit 130 and no output file (nor a temporary).
  const fs::path out = scratch() / "interrupted.exr";
  const int status = render_and_signal(out, SIGINT);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by a signal instead of stopping cleanly";
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(scratch()))
    EXPECT_EQ(e.path().filename().string().find("interrupted"), std::string::npos) << e.path();
}

TEST(SssReferenceApp, SignalsNeverLeaveAHalfFileNorDestroyTheOldOne) {
  // An output from an earlier run is in place; a second run into the same file is stopped
  // 1.5 s in (mid-render, as CtrlCStopsWithoutWritingAFile) by SIGINT, SIGTERM or SIGKILL.
  // SIGINT and SIGTERM stop it cleanly (130, 143: 128 + the signal); SIGKILL cannot be
  // handled. In every case the old file is byte for byte as it was and nothing else (no
  // half file, no temporary) is left in the folder.
  const fs::path folder = scratch() / "signals";
  fs::create_directories(folder);
  const fs::path out = folder / "render.exr";
  { std::ofstream(out, std::ios::binary) << "an earlier render"; }
  for (const int sig : {SIGINT, SIGTERM, SIGKILL}) {
    const int status = render_and_signal(out, sig);
    if (sig == SIGKILL) {
      EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "it finished within 1.5 s";
    } else {
      ASSERT_TRUE(WIFEXITED(status)) << "signal " << sig << " killed it instead of stopping it";
      EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    }
    EXPECT_EQ(slurp(out), "an earlier render") << "signal " << sig;
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(folder)) ++entries;
    EXPECT_EQ(entries, 1) << "signal " << sig << ": something besides render.exr was left";
  }
}

}  // namespace

#endif  // SSS_REFERENCE_EXE
