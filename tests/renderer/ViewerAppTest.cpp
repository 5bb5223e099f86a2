// sss-viewer: every documented command and error (DESIGN.md §4, §7 "apps").
#include <gtest/gtest.h>

#include "image/Image.h"

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/CliRun.h"
#include "common/FrameLessHighlight.h"
#include "common/TwoBoxesGltf.h"

#ifdef SSS_VIEWER_EXE

namespace {

using ViewerRun = sss::testing::CliRun;

ViewerRun run(const std::string& args) { return sss::testing::run_shell(std::string(SSS_VIEWER_EXE) + " " + args); }

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("sss_viewer_test_" + name)).string();
}

TEST(ViewerApp, HeadlessWritesPngAndExr) {
  for (const char* ext : {".png", ".exr"}) {
    const std::string out = temp_path(std::string("sphere") + ext);
    std::filesystem::remove(out);
    const ViewerRun r = run("builtin:sphere --headless --out " + out + " --width 96 --height 54");
    EXPECT_EQ(r.code, 0) << r.out;
    auto image = sss::image::read_image(out);
    ASSERT_TRUE(std::holds_alternative<sss::image::Image>(image)) << out;
    EXPECT_EQ(std::get<sss::image::Image>(image).width, 96);
    EXPECT_EQ(std::get<sss::image::Image>(image).height, 54);
    std::filesystem::remove(out);
  }
}

// --no-specular writes the frame less its specular target: never brighter than the whole
// frame (specular >= 0), darker where the sphere has its highlight, and the same where the
// specular is 0 (the background, the sphere's unlit side).
TEST(ViewerApp, NoSpecularIsTheFrameLessItsHighlight) {
  const std::string whole = temp_path("whole.exr"), scattered = temp_path("scattered.exr");
  const std::string args = "builtin:sphere --headless --width 96 --height 54 --out ";
  ASSERT_EQ(run(args + whole).code, 0);
  const ViewerRun r = run(args + scattered + " --no-specular");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto a = sss::image::read_image(whole), b = sss::image::read_image(scattered);
  ASSERT_TRUE(std::holds_alternative<sss::image::Image>(a) && std::holds_alternative<sss::image::Image>(b));
  const auto& w = std::get<sss::image::Image>(a);
  const auto h = sss::testing::check_frame_less_highlight(w, std::get<sss::image::Image>(b));
  EXPECT_GT(h.largest_drop, 0.01) << "no pixel lost a highlight";
  // The sphere covers under half of the 16:9 frame; the background has no specular.
  EXPECT_GT(double(h.unchanged), 0.5 * 0.75 * double(w.rgba.size())) << "the background should be untouched";
  std::filesystem::remove(whole);
  std::filesystem::remove(scattered);
}

TEST(ViewerApp, StatsPrintEveryPassAndTheCpuFrameTime) {
  const std::string out = temp_path("stats.png");
  for (const char* mode : {"separable", "gaussians"}) {
    const ViewerRun r = run("builtin:sphere --headless --out " + out +
                      " --width 64 --height 36 --frames 2 --stats --mode " + mode);
    EXPECT_EQ(r.code, 0) << r.out;
    for (const char* row : {"shadow", "gbuffer", "lighting", "composite", "cpu frame", "frame targets"})
      EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
    EXPECT_NE(r.out.find(std::string("sss ") + mode), std::string::npos) << r.out;
  }
  const ViewerRun off = run("builtin:sphere --headless --out " + out + " --width 64 --height 36 --sss off --stats");
  EXPECT_EQ(off.code, 0) << off.out;
  EXPECT_EQ(off.out.find("sss separable"), std::string::npos) << off.out;
  std::filesystem::remove(out);
}

TEST(ViewerApp, MaterialOverridesAreAccepted) {
  const std::string out = temp_path("override.exr");
  const ViewerRun r = run("builtin:sphere --headless --out " + out +
                    " --width 48 --height 27 --preset marble --model dipole --gaussians 3"
                    " --albedo pre-post");
  EXPECT_EQ(r.code, 0) << r.out;
  const ViewerRun c = run("builtin:sphere --headless --out " + out +
                    " --width 48 --height 27 --sigma-a 0.01,0.02,0.03 --sigma-s 1,1,1");
  EXPECT_EQ(c.code, 0) << c.out;
  // Quantized diffusion end to end: the fit of its Gaussian sum, the tabulated separable
  // kernel, the frame.
  const ViewerRun q = run("builtin:sphere --headless --out " + out + " --width 48 --height 27 --model qd");
  EXPECT_EQ(q.code, 0) << q.out;
  std::filesystem::remove(out);
}

std::string broken_gltf() {
  const std::string path = temp_path("broken.gltf");
  std::ofstream(path) << "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ { \"mesh\": 7 } ] }";
  return path;
}

TEST(ViewerApp, DocumentedErrors) {
  const std::string out = temp_path("error.png");
  std::filesystem::remove(out);  // left by an earlier failed run, it would hide a new one
  struct Case {
    std::string args;
    int status;
    std::string message;
  };
  const Case cases[] = {
      {"builtin:sphere --out " + out, 2, "--out needs --headless"},
      {"builtin:sphere --screenshot " + temp_path("x.jpg"), 2, "--screenshot"},
      {"builtin:sphere --vsync maybe", 2, "--vsync"},
      {"builtin:sphere --headless", 2, "--out"},
      {"builtin:sphere --headless --out " + temp_path("x.jpg"), 2, ".png or .exr"},
      {"builtin:sphere --headless --out " + out + " --sss texture --texture-size 100", 2,
       "--texture-size"},
      {"builtin:sphere --headless --out " + out + " --sss texture --texture-update sometimes", 2,
       "--texture-update"},
      {"builtin:sphere --headless --out " + out + " --sss texture --texture-object sphere=big", 2,
       "sphere=big"},
      {"builtin:sphere --headless --out " + out + " --texture-object =512", 2, "--texture-object"},
      {"builtin:sphere --headless --out " + out + " --atlas-out " + temp_path("atlas"), 2,
       "--atlas-out needs --sss texture"},
      {"builtin:sphere --headless --out " + out + " --sss fuzzy", 2, "--sss"},
      {"builtin:sphere --headless --out " + out + " --mode blurry", 2, "--mode"},
      {"builtin:sphere --headless --out " + out + " --model nope", 2, "--model"},
      {"builtin:sphere --headless --out " + out + " --gaussians 9", 2, "--gaussians"},
      {"builtin:sphere --headless --out " + out + " --preset nope", 2, "preset"},
      {"builtin:sphere --headless --out " + out + " --taps 4", 2, "--taps"},
      {"builtin:sphere --headless --out " + out + " --exposure 0", 2, "--exposure"},
      {"builtin:sphere --headless --out " + out + " --exposure nan", 2, "--exposure"},
      {"builtin:sphere --headless --out " + out + " --exposure -1", 2, "--exposure"},
      {"builtin:sphere --headless --out " + out + " --width 16384 --height 16384", 2,
       "--width x --height"},
      {"builtin:sphere --headless --out " + out + " --albedo half", 2, "--albedo"},
      {"builtin:sphere --headless --out " + out + " --sky-occlusion maybe", 2, "--sky-occlusion"},
      {"builtin:sphere --headless --out " + out + " --no-specular", 2, "--no-specular"},
      {"builtin:sphere --no-specular", 2, "--no-specular needs --headless"},
      {"builtin:nothing --headless --out " + out, 2, "builtin:nothing"},
      {"/nonexistent/scene.gltf --headless --out " + out, 2, "scene.gltf"},
      {"builtin:sphere --headless --out " + out + " --width 0", 2, "width"},
      {"builtin:sphere --headless --out " + out + " --device nonesuch", 2, "nonesuch"},
      {broken_gltf() + " --headless --out " + out, 2, "broken.gltf"},
      {"builtin:sphere --headless --out " + out + " --debug-view kernel-radius --debug-range 0,5",
       2, "LO must be > 0"},
      {"builtin:sphere --headless --out " + out + " --debug-view thickness --debug-range 5,1", 2,
       "LO < HI"},
      {"builtin:sphere --headless --out " + out + " --debug-view profile-id --debug-range 0,5", 2,
       "has no heat map"},
      {"builtin:sphere --headless --out " + out + " --debug-view thickness --debug-range 5", 2,
       "--debug-range"},
      {"builtin:sphere --headless --out " + out + " --aa smaa", 2,
       "--aa: expected auto, off or fxaa, got 'smaa'"},
      {"builtin:sphere --headless --out " + out + " --background 0.5,0.5", 2,
       "--background: expected R,G,B or one number, got '0.5,0.5'"},
      {"builtin:sphere --headless --out " + out + " --background 0,1.5,0", 2,
       "--background: each of R, G, B must lie in [0, 1] (sRGB), got 1.5"},
      {"builtin:sphere --headless --out " + out + " --background grey", 2, "--background"},
      {"builtin:sphere --headless --out " + out + " --background environment", 2,
       "--background environment: no environment to show"},
      {"builtin:sphere --headless --out " + out + " --environment 1,2", 2,
       "--environment: the environment '1,2' is neither R,G,B"},
      {"builtin:sphere --headless --out " + out + " --environment 1,-1,1", 2,
       "each component must be a finite number >= 0"},
      {"builtin:sphere --headless --out " + out + " --environment /nonexistent/sky.exr", 2,
       "--environment: /nonexistent/sky.exr"},
      {"builtin:sphere --headless --out " + out + " --environment sky.png", 2, "must be OpenEXR"},
      {"builtin:sphere --headless --out " + out + " --environment 1,1,1 --environment-intensity -1", 2,
       "intensity must be a finite number >= 0"},
      {"builtin:sphere --headless --out " + out + " --environment-intensity 2", 2,
       "--environment-intensity: needs --environment"},
  };
  for (const Case& c : cases) {
    const ViewerRun r = run(c.args);
    EXPECT_EQ(r.code, c.status) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.args << "\n" << r.out;
  }
  // A file that does not load names the file; a pointer to --help would not help.
  const ViewerRun missing = run("/nonexistent/scene.gltf --headless --out " + out);
  EXPECT_EQ(missing.out.find("--help"), std::string::npos) << missing.out;
  // A mistyped option gets the nearest one.
  const ViewerRun typo = run("builtin:sphere --headles --out " + out);
  EXPECT_NE(typo.out.find("did you mean '--headless'"), std::string::npos) << typo.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Issue 20: a user's own glTF, with no extras.sss. The MEDIUM flags were a silent no-op on
// it (exit 0, the same image); they are now an error that lists the materials, and
// --sss-material gives the chosen material subsurface scattering: the frame changes where
// that box is drawn, and only there (the "metal" box keeps its pixels).
TEST(ViewerApp, SssMaterialGivesAPlainGltfSubsurfaceScattering) {
  const std::filesystem::path file = temp_path("boxes.glb");
  sss::testing::write_two_boxes(file, 0.05f);  // 5 cm boxes
  const std::string plain = temp_path("boxes-plain.exr"), lit = temp_path("boxes-sss.exr");
  const std::string args = file.string() + " --headless --width 96 --height 54 --out ";
  const ViewerRun a = run(args + plain);
  ASSERT_EQ(a.code, 0) << a.out;
  const ViewerRun silent = run(args + lit + " --preset marble");
  EXPECT_EQ(silent.code, 2) << silent.out;
  EXPECT_NE(silent.out.find("--preset: matches no material"), std::string::npos) << silent.out;
  EXPECT_NE(silent.out.find("0 'plastic', 1 'metal'"), std::string::npos) << silent.out;
  EXPECT_FALSE(std::filesystem::exists(lit));
#ifdef SSS_REFERENCE_EXE  // the reference reads the same options
  const ViewerRun ref = sss::testing::run_shell(std::string(SSS_REFERENCE_EXE) + " " + file.string() +
                                                " --out " + temp_path("boxes-ref.exr") + " --preset marble");
  EXPECT_EQ(ref.code, 2) << ref.out;
  EXPECT_NE(ref.out.find("--preset: matches no material"), std::string::npos) << ref.out;
#endif
  const ViewerRun b = run(args + lit + " --sss-material 'plastic=marble;scale=0.1'");
  ASSERT_EQ(b.code, 0) << b.out;
  const auto ia = sss::image::read_image(plain), ib = sss::image::read_image(lit);
  ASSERT_TRUE(std::holds_alternative<sss::image::Image>(ia) && std::holds_alternative<sss::image::Image>(ib));
  const auto& pa = std::get<sss::image::Image>(ia).rgba;
  const auto& pb = std::get<sss::image::Image>(ib).rgba;
  ASSERT_EQ(pa.size(), pb.size());
  // The plastic box (left of the frame's centre) scatters now, the right half holds the
  // metal box and the background, drawn as before. Every pixel of the plastic box changes:
  // a lit one shows albedo x (R * E) instead of albedo x E, and marble's total reflectance
  // is below 1 in every channel; an unlit one gains the light through the box (5 cm at
  // scale 0.1 is 5 mm of marble). Geometry is where the plain frame's alpha is > 0.
  const int w = std::get<sss::image::Image>(ia).width;
  std::size_t box = 0, changed_left = 0, changed_right = 0;
  for (std::size_t i = 0; i < pa.size(); i += 4) {
    const int x = int((i / 4) % std::size_t(w));
    const bool differs = std::abs(pa[i] - pb[i]) + std::abs(pa[i + 1] - pb[i + 1]) +
                             std::abs(pa[i + 2] - pb[i + 2]) > 1e-4f;
    if (x < w / 2) {
      box += pa[i + 3] > 0.0f ? 1 : 0;
      changed_left += differs && pa[i + 3] > 0.0f ? 1 : 0;
    } else {
      changed_right += differs ? 1 : 0;
    }
  }
  EXPECT_GT(box, 0u);
  EXPECT_EQ(changed_left, box);
  EXPECT_EQ(changed_right, 0u);
  std::filesystem::remove(plain);
  std::filesystem::remove(lit);
  std::filesystem::remove(file);
}

}  // namespace

#endif  // SSS_VIEWER_EXE
