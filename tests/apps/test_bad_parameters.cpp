// Issue 7: every non-finite or out-of-range parameter on every CLI that takes one (sss-fit's
// profile / fit / validate, sss-reference, sss-compare) exits 2 with the option named on
// stderr, writes nothing on stdout and creates no output file. One table; each row runs
// one process (the refusal comes before any work, so the whole table takes a few seconds).
#include "common/CliRun.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using sss::testing::CliRun;

fs::path scratch() {
  static const fs::path dir = sss::testing::scratch_dir("sss-bad-parameters");
  return dir;
}

struct Row {
  std::string args;    // after the executable
  std::string names;   // what stderr must contain: the option (and field)
};

// The MEDIUM values every sss-fit command and sss-reference share (app/common/MediumArgs),
// each with the option its error must name.
std::vector<Row> medium_rows() {
  const std::string m = "--sigma-a 0.1 --sigma-s 1";
  return {
      {"--sigma-a -1 --sigma-s 1", "--sigma-a[R]"},          // σa < 0
      {"--sigma-a 1 --sigma-s -1", "--sigma-s[R]"},          // σs < 0
      {"--sigma-a 0 --sigma-s 0", "--sigma-a/--sigma-s[R]"}, // σt = 0
      {"--sigma-a 0 --sigma-s 1", "--sigma-a[R]"},           // albedo exactly 1
      {"--sigma-a 1e-300 --sigma-s 1", "--sigma-a[R]"},      // albedo 1 - 1e-300
      {"--sigma-a nan --sigma-s 1", "--sigma-a[R]"},
      {"--sigma-a 0.1,inf,1 --sigma-s 1", "--sigma-a[G]"},
      {"--sigma-a 1e400 --sigma-s 1", "--sigma-a"},         // overflows strtod
      {"--sigma-a 1e300 --sigma-s 1", "--sigma-a[R]"},       // above 1e6 mm^-1
      {"--sigma-a 0.1 --sigma-s 1e7", "--sigma-s[R]"},
      {"--sigma-a 1e-9 --sigma-s 1e-9", "--sigma-a/--sigma-s[R]"},  // reduced mfp > 1 km
      {"--sigma-a 0.1,0.2 --sigma-s 1", "--sigma-a"},        // two channels
      {"--sigma-a 0.1 --sigma-s x", "--sigma-s"},
      {"--sigma-a 0.1", "--sigma-s"},                        // the pair is incomplete
      {m + " --g 1", "--g[R]"},
      {m + " --g -1", "--g[R]"},
      {m + " --g nan", "--g[R]"},
      {m + " --eta 0", "--eta[R]"},
      {m + " --eta -1", "--eta[R]"},
      {m + " --eta nan", "--eta[R]"},
      {m + " --eta inf", "--eta[R]"},
      {m + " --eta 0.9", "--eta[R]"},                       // below the supported [1, 2.5]
      {m + " --eta 3", "--eta[R]"},                         // above it
      {m + " --thickness 0", "--thickness"},
      {m + " --thickness -1", "--thickness"},
      {m + " --thickness nan", "--thickness"},
      {"--color 1.2 --mfp 1", "--color[R]"},                // albedo (colour) outside (0,1)
      {"--color 1 --mfp 1", "--color[R]"},                  // colour 1 needs albedo 1
      {"--color 0 --mfp 1", "--color[R]"},
      {"--color 0.5,-0.1,0.5 --mfp 1", "--color[G]"},
      {"--color nan --mfp 1", "--color[R]"},
      {"--color 0.5 --mfp 0", "--mfp[R]"},                  // mean free path <= 0
      {"--color 0.5 --mfp -1", "--mfp[R]"},
      {"--color 0.5 --mfp nan", "--mfp[R]"},
      {"--color 0.5 --mfp 1,1,inf", "--mfp[B]"},
      {"--color 0.5 --mfp 1e300", "--mfp[R]"},
      {"--color 0.5 --mfp 1e-300", "--mfp[R]"},
      {"--color 0.5 --mfp 1 --eta 3", "--eta"},
      {"--color 0.5", "--mfp"},
      {"--preset nope", "--preset"},                        // unknown preset
      {"--preset skin1 --eta 0", "--eta[R]"},
      {"--preset skin1 --sigma-a 1 --sigma-s 1", "MEDIUM"},   // two media at once
  };
}

// Runs every row; each must exit 2, name its option on stderr, print nothing on stdout
// and leave `out` (the output a successful run would write) absent.
void expect_refused(const std::string& exe, const std::string& prefix, const std::vector<Row>& rows,
                    const fs::path& out) {
  for (const Row& row : rows) {
    const std::string args = prefix + " " + row.args;
    const CliRun r = sss::testing::run_cli(exe, args, scratch() / "stderr.txt");
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(row.names), std::string::npos) << args << "\nstderr: " << r.err;
    EXPECT_TRUE(r.out.empty()) << args << "\nstdout: " << r.out;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

}  // namespace

TEST(BadParameters, SssFitProfileRefusesEveryOutOfRangeValue) {
  std::vector<Row> rows = medium_rows();
  const std::string m = "--sigma-a 0.1 --sigma-s 1";
  for (Row r : std::vector<Row>{
           {m + " --model nope", "--model"},             // unknown model
           {m + " --radii -1:1:3", "--radii"},           // negative radius
           {m + " --radii nan:1:3", "--radii"},
           {m + " --radii 0:inf:3", "--radii"},
           {m + " --radii 1:0:3", "--radii"},
           {m + " --radii 0:1:0", "--radii"},
           {m + " --radii 0:1:1e9", "--radii"},          // huge count
           {m + " --radii 0:1:2.5", "--radii"},
           {m + " --radii 0:1", "--radii"},
           {m + " --radii 0:1:3 --log", "--radii"},      // log spacing from 0
           {m + " --pbd-samples 0", "--pbd-samples"},
           {m + " --photons 0", "--photons"},
           {m + " --threads -1", "--threads"}})
    rows.push_back(r);
  for (Row& r : rows)
    if (r.args.find("--radii") == std::string::npos) r.args += " --radii 0:1:3";
  expect_refused(SSS_FIT_EXE, "profile", rows, scratch() / "none");
}

TEST(BadParameters, SssFitFitRefusesEveryOutOfRangeValue) {
  const fs::path out = scratch() / "kernel.json";
  std::vector<Row> rows = medium_rows();
  const std::string m = "--sigma-a 0.1 --sigma-s 1";
  for (Row r : std::vector<Row>{
           {m + " --model nope", "--model"},
           {m + " --gaussians 0", "--gaussians"},        // Gaussian count outside 1..8
           {m + " --gaussians 9", "--gaussians"},
           {m + " --gaussians -1", "--gaussians"},
           {m + " --samples 0", "--samples"},
           {m + " --samples 100000", "--samples"},
           {m + " --taps 4", "--taps"},
           {m + " --taps 1001", "--taps"},
           {m + " --multipole-pairs 3", "--multipole-pairs"}})  // an option that does not exist
    rows.push_back(r);
  for (Row& r : rows) r.args += " --out " + out.string();
  expect_refused(SSS_FIT_EXE, "fit", rows, out);
}

TEST(BadParameters, SssFitValidateRefusesEveryOutOfRangeValue) {
  std::vector<Row> rows = medium_rows();
  rows.push_back({"--sigma-a 0.1 --sigma-s 1 --photons 0", "--photons"});
  for (Row& r : rows) r.args += " --photons 1000";
  expect_refused(SSS_FIT_EXE, "validate", rows, scratch() / "none");
}

#ifdef SSS_REFERENCE_EXE
TEST(BadParameters, SssReferenceRefusesEveryOutOfRangeValue) {
  const fs::path out = scratch() / "ref.exr";
  std::vector<Row> rows = medium_rows();
  for (Row r : std::vector<Row>{
           {"--model nope", "--model"},
           {"--gaussians 0", "--gaussians"},
           {"--gaussians 9", "--gaussians"},
           {"--albedo nope", "--albedo"},
           {"--width 0", "--width"},                     // zero image size
           {"--width -5", "--width"},
           {"--width 100000", "--width"},                // huge
           {"--height 0", "--height"},
           {"--height 100000", "--height"},
           {"--width 16384 --height 16384", "--width x --height"},  // huge in total
           {"--spacing 0", "--spacing"},
           {"--spacing -1", "--spacing"},
           {"--spacing nan", "--spacing"},
           {"--spacing inf", "--spacing"},
           {"--max-points 0", "--max-points"},
           {"--error-bound -1", "--error-bound"},
           {"--error-bound nan", "--error-bound"},
           {"--exposure 0", "--exposure"},
           {"--exposure -1", "--exposure"},
           {"--exposure nan", "--exposure"},
           {"--threads -1", "--threads"},
           {"--seed -1", "--seed"},
           {"--png " + (scratch() / "x.jpg").string(), "--png"}})
    rows.push_back(r);
  expect_refused(SSS_REFERENCE_EXE, "builtin:edge --quiet --out " + out.string(), rows, out);
  expect_refused(SSS_REFERENCE_EXE, "builtin:edge --quiet", {{"--out " + (scratch() / "r.txt").string(), "--out"}},
                 scratch() / "r.txt");
}
#endif

#ifdef SSS_COMPARE_EXE
TEST(BadParameters, SssCompareRefusesEveryOutOfRangeValue) {
  // Two 1x1 PNGs (never read: the options are checked first).
  const std::string a = (scratch() / "a.png").string();
  const fs::path heat = scratch() / "heat.png";
  std::vector<Row> rows;
  for (const char* opt : {"--tolerance", "--threshold", "--max-abs", "--max-fraction"})
    for (const char* v : {"-1", "nan", "inf"}) rows.push_back({std::string(opt) + " " + v, opt});
  for (Row r : std::vector<Row>{
           {"--max-fraction 1.5", "--max-fraction"},
           {"--min-ssim 2", "--min-ssim"},
           {"--min-ssim nan", "--min-ssim"},
           {"--exposure 0", "--exposure"},
           {"--exposure nan", "--exposure"},
           {"--exposure inf", "--exposure"},
           {"--heatmap " + heat.string() + " --heatmap-max 0", "--heatmap-max"},
           {"--heatmap " + heat.string() + " --heatmap-max nan", "--heatmap-max"},
           {"--heatmap-max 1", "--heatmap"},
           {"--heatmap " + (scratch() / "heat.txt").string(), "--heatmap"}})
    rows.push_back(r);
  expect_refused(SSS_COMPARE_EXE, a + " " + a, rows, heat);
}
#endif
