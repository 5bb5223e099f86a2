// sss-compare agrees with its docs (issue 20 part 4): the README's sphere example passes as
// written, and the three command lines the README gives reproduce a row of
// tests/golden/REPORT.md (the golden suite's number, not a different one). Headless: the
// viewer renders on lavapipe with the validation layer on.
#include <gtest/gtest.h>

#include "ViewerRun.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace sss::testing {
namespace {

#if defined(SSS_VIEWER_EXE) && defined(SSS_REFERENCE_EXE) && defined(SSS_COMPARE_EXE)

std::string tool(const char* exe, const std::string& args) { return std::string(exe) + " " + args; }

CliRun viewer(const std::string& args) {
  return run_shell("SSS_VALIDATION=1 env -u DISPLAY -u WAYLAND_DISPLAY " + tool(SSS_VIEWER_EXE, args));
}

// The relative RMSE of `sss-compare ARGS --json`, or -1 with the output in *out.
double compare_rmse(const std::string& args, int* code, std::string* out) {
  const CliRun r = run_shell(tool(SSS_COMPARE_EXE, args + " --json"));
  *code = r.code;
  *out = r.out;
  const auto doc = nlohmann::json::parse(r.out, nullptr, false);
  if (doc.is_discarded() || !doc.contains("metrics")) return -1.0;
  return doc["metrics"]["relative_rmse"].get<double>();
}

// README, "The CPU reference": the first comparison of the sphere example, as written there
// (--exclude-silhouettes and --tolerance 0.03, the suite's derived limit for
// sphere/gaussians at its size, 3.13% in REPORT.md). Exit 0. Before issue 20 the README
// gave the bare `sss-compare gpu.exr ref.exr`, whose 1% default the example misses
// (1.18% today, 1.57% when the issue was filed).
TEST(CompareDocs, TheReadmeSphereExamplePasses) {
  const std::string gpu = viewer_temp_path("compare_docs", "sphere_gpu.exr");
  const std::string ref = viewer_temp_path("compare_docs", "sphere_ref.exr");
  const std::string diff = viewer_temp_path("compare_docs", "sphere_diff.png");
  const CliRun v = viewer("builtin:sphere --headless --out " + gpu + " --mode gaussians");
  ASSERT_EQ(v.code, 0) << v.out;
  EXPECT_FALSE(has_validation_message(v.out)) << v.out;
  const CliRun rf = run_shell(tool(SSS_REFERENCE_EXE, "builtin:sphere --out " + ref));
  ASSERT_EQ(rf.code, 0) << rf.out;
  int code = 0;
  std::string out;
  const double e = compare_rmse(gpu + " " + ref + " --exclude-silhouettes --tolerance 0.03 --heatmap " + diff,
                                &code, &out);
  EXPECT_EQ(code, 0) << out;
  EXPECT_GT(e, 0.0) << out;  // a real comparison, not two copies of one image
  EXPECT_TRUE(std::filesystem::exists(diff));
  for (const auto& p : {gpu, ref, diff}) std::filesystem::remove(p);
}

// The row "bunny | separable | mc-table | 160×90" of REPORT.md: its relative RMSE, read
// from the file, and the same number from the README's command lines (the suite's size,
// its 512² shadow maps, the reference's 1 mfp spacing, silhouettes left out). The issue
// saw 49% from the CLI against the report's 23%; without --exclude-silhouettes it is 33%
// today. Tolerance: REPORT.md's rounding to 0.01 percentage points (±0.005 points, 5e-5),
// and nothing else: the two paths run the same code on the same scene, so any larger
// difference means the report or the documented command lines no longer say what the
// frame is (measured: 21.80% against the report's 21.80%, after the separable cell averages of issue 20).
TEST(CompareDocs, TheCommandLinesReproduceTheReportsBunnyRow) {
  std::ifstream report(std::string(SSS_SOURCE_DIR) + "/tests/golden/REPORT.md");
  ASSERT_TRUE(report) << "tests/golden/REPORT.md";
  const std::string row = "| bunny | separable | mc-table | 160×90 | ";
  double expected = -1.0;
  for (std::string line; std::getline(report, line);)
    if (line.rfind(row, 0) == 0) {
      expected = std::stod(line.substr(row.size())) / 100.0;
      break;
    }
  ASSERT_GT(expected, 0.0) << "no row '" << row << "' in REPORT.md";

  const std::string gpu = viewer_temp_path("compare_docs", "bunny_gpu.exr");
  const std::string ref = viewer_temp_path("compare_docs", "bunny_ref.exr");
  const CliRun v = viewer("builtin:bunny --headless --width 160 --height 90 --shadow-map-size 512 --out " + gpu);
  ASSERT_EQ(v.code, 0) << v.out;
  EXPECT_FALSE(has_validation_message(v.out)) << v.out;
  const CliRun rf =
      run_shell(tool(SSS_REFERENCE_EXE, "builtin:bunny --width 160 --height 90 --spacing 1 --out " + ref));
  ASSERT_EQ(rf.code, 0) << rf.out;
  int code = 0;
  std::string out;
  const double with = compare_rmse(gpu + " " + ref + " --exclude-silhouettes", &code, &out);
  EXPECT_NEAR(with, expected, 5e-5 + 1e-12) << out;
  EXPECT_NE(out.find("\"silhouette\""), std::string::npos) << out;
  // Without it the silhouettes' specular spikes count: far above the report.
  const double without = compare_rmse(gpu + " " + ref, &code, &out);
  EXPECT_GT(without, expected + 0.05) << out;
  for (const auto& p : {gpu, ref}) std::filesystem::remove(p);
}

#endif

}  // namespace
}  // namespace sss::testing
