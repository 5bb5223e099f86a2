// Every documented sss-fit command and every documented error (DESIGN.md §4): exit code
// 0 on success, 2 for bad usage or input with the field named on stderr, 1 for runtime
// failures; --json prints exactly one JSON document.
#include "common/CliRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

using sss::testing::CliRun;
using sss::testing::slurp;

fs::path scratch_dir() {
  static const fs::path dir = sss::testing::scratch_dir("sss-fit-test");
  return dir;
}

CliRun sss_fit(const std::string& args) {
  return sss::testing::run_cli(SSS_FIT_EXE, args, scratch_dir() / "stderr.txt");
}

nlohmann::json parse_only_json(const std::string& s) {
  return nlohmann::json::parse(s);  // throws if anything but one document is on stdout
}

}  // namespace

TEST(SssFit, HelpListsTheCommands) {
  CliRun r = sss_fit("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* c : {"presets", "profile", "fit", "validate"})
    EXPECT_NE(r.out.find(c), std::string::npos) << c;
  EXPECT_EQ(sss_fit("fit --help").code, 0);
}

TEST(SssFit, NoCommandIsUsageError) { EXPECT_EQ(sss_fit("").code, 2); }

TEST(SssFit, Presets) {
  CliRun r = sss_fit("presets");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("skin1"), std::string::npos);
  CliRun j = sss_fit("presets --json");
  ASSERT_EQ(j.code, 0);
  auto doc = parse_only_json(j.out);
  ASSERT_EQ(doc.size(), 12u);
  EXPECT_EQ(doc[0]["name"], "apple");
}

TEST(SssFit, ProfileJsonContract) {
  CliRun r = sss_fit("profile --preset skin1 --model dipole --radii 0:10:11 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto doc = parse_only_json(r.out);
  EXPECT_EQ(doc["model"], "dipole");
  ASSERT_EQ(doc["radii_mm"].size(), 11u);
  ASSERT_EQ(doc["R"].size(), 11u);
  EXPECT_EQ(doc["R"][0].size(), 3u);
  EXPECT_GT(doc["R"][0][0].get<double>(), doc["R"][10][0].get<double>());
  // Jensen 2001 eq. 5 for skin1 red at η = 1.3 (see test_dipole): 0.4360.
  EXPECT_NEAR(doc["total_reflectance"][0].get<double>(), 0.4360, 5e-4);
}

TEST(SssFit, ProfileTextAndEveryModel) {
  for (const char* m : {"dipole", "better-dipole", "pbd", "burley"}) {
    CliRun r = sss_fit(std::string("profile --preset marble --radii 0.1:5:5 --log --model ") + m);
    EXPECT_EQ(r.code, 0) << m << r.err;
    EXPECT_NE(r.out.find("# r_mm"), std::string::npos);
  }
  CliRun mp = sss_fit("profile --preset skin1 --model multipole --thickness 2 --radii 0:4:5 --json");
  ASSERT_EQ(mp.code, 0) << mp.err;
  auto doc = parse_only_json(mp.out);
  EXPECT_TRUE(doc.contains("T"));
  EXPECT_GT(doc["total_transmittance"][0].get<double>(), 0.0);
  CliRun mc = sss_fit("profile --preset skin1 --model mc --photons 20000 --radii 0.5:2:3 --json");
  ASSERT_EQ(mc.code, 0) << mc.err;
  EXPECT_EQ(parse_only_json(mc.out)["R"].size(), 3u);
}

TEST(SssFit, FitJsonContractPreservesEnergy) {
  CliRun r = sss_fit("fit --preset marble --model better-dipole --gaussians 4 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto doc = parse_only_json(r.out);
  for (const char* k : {"model", "variances_mm2", "weights", "total_reflectance", "relative_error"})
    EXPECT_TRUE(doc.contains(k)) << k;
  ASSERT_EQ(doc["variances_mm2"].size(), 4u);
  for (int c = 0; c < 3; ++c) {
    double sum = 0;
    for (auto& w : doc["weights"]) sum += w[c].get<double>();
    EXPECT_NEAR(sum, doc["total_reflectance"][c].get<double>(), 1e-9);
  }
}

TEST(SssFit, FitWritesKernelHeaderAndPlot) {
  const fs::path json = scratch_dir() / "k.json", header = scratch_dir() / "k.h",
                 svg = scratch_dir() / "fit.svg";
  CliRun r = sss_fit("fit --preset skin1 --gaussians 6 --taps 9 --out " + json.string() +
                  " --plot " + svg.string() + " --plot-mc --photons 20000");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::parse(slurp(json)).contains("separable"));
  const std::string plot = slurp(svg);
  EXPECT_EQ(plot.rfind("<svg", 0), 0u);
  EXPECT_NE(plot.find("</svg>"), std::string::npos);
  EXPECT_NE(plot.find("r (mm)"), std::string::npos);
  EXPECT_NE(plot.find("Monte Carlo"), std::string::npos);
  CliRun h = sss_fit("fit --preset skin1 --out " + header.string());
  ASSERT_EQ(h.code, 0) << h.err;
  EXPECT_NE(slurp(header).find("sss_kernel_variances_mm2"), std::string::npos);
  // Nothing but the outputs: no temporary files left behind.
  for (auto& e : fs::directory_iterator(scratch_dir()))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(SssFit, ValidateJson) {
  CliRun r = sss_fit("validate --preset skin1 --photons 20000 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto doc = parse_only_json(r.out);
  ASSERT_GE(doc["models"].size(), 4u);
  EXPECT_GT(doc["monte_carlo"]["total_reflectance"][0].get<double>(), 0.3);
  CliRun t = sss_fit("validate --preset skin1 --photons 20000");
  EXPECT_EQ(t.code, 0);
  EXPECT_NE(t.out.find("better-dipole"), std::string::npos);
}

struct BadInput {
  const char* args;
  const char* expected;  // a piece of the message on stderr
};

class SssFitErrors : public ::testing::TestWithParam<BadInput> {};

TEST_P(SssFitErrors, ExitTwoAndNameTheField) {
  CliRun r = sss_fit(GetParam().args);
  EXPECT_EQ(r.code, 2) << GetParam().args << "\n" << r.err;
  EXPECT_NE(r.err.find(GetParam().expected), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Documented, SssFitErrors,
    ::testing::Values(
        BadInput{"fit --preset jade", "unknown preset 'jade'"},
        BadInput{"fit --preset spectralon", "albedo of 1"},
        BadInput{"fit --sigma-a -1,0.1,0.1 --sigma-s 1", "--sigma-a[R]"},
        BadInput{"fit --sigma-a 0.1,nan,0.1 --sigma-s 1", "--sigma-a[G]"},
        BadInput{"fit --sigma-a 0 --sigma-s 1", "albedo of 1"},
        BadInput{"fit --sigma-a 0.1 --sigma-s -2", "--sigma-s[R]"},
        BadInput{"fit --sigma-a 0.1 --sigma-s 1 --g 1", "--g[R]"},
        BadInput{"fit --sigma-a 0.1 --sigma-s 1 --eta 0", "--eta[R]"},
        BadInput{"fit --sigma-a 0.1 --sigma-s 1 --eta abc", "--eta"},
        BadInput{"fit --sigma-a 0.1,0.2 --sigma-s 1", "expected R,G,B"},
        BadInput{"fit --sigma-a 0.1", "--sigma-s"},
        BadInput{"fit --model dipole", "MEDIUM"},
        BadInput{"fit --preset skin1 --sigma-a 1 --sigma-s 1", "exclude each other"},
        BadInput{"fit --preset skin1 --model quantized", "unknown model 'quantized'"},
        BadInput{"fit --preset skin1 --gaussians 0", "--gaussians"},
        BadInput{"fit --preset skin1 --gaussians 9", "--gaussians"},
        BadInput{"fit --preset skin1 --taps 8", "--taps"},
        BadInput{"fit --color 1.2,0.5,0.5 --mfp 1", "--color[R]"},
        BadInput{"fit --color 0.5 --mfp 0", "--mfp[R]"},
        BadInput{"fit --preset skin1 --thickness -1", "--thickness"},
        BadInput{"profile --preset skin1 --model multipole --radii 0:1:2", "thickness"},
        BadInput{"profile --preset skin1 --radii 0:1", "START:STOP:COUNT"},
        BadInput{"profile --preset skin1 --radii 2:1:3", "START <= STOP"},
        BadInput{"profile --preset skin1 --radii 0:1:2.5", "COUNT"},
        BadInput{"profile --preset skin1", "--radii"},
        BadInput{"validate --preset skin1 --photons 0", "--photons"},
        BadInput{"fit --preset skin1 --bogus", "bogus"}));

TEST(SssFit, UnwritableOutputIsARuntimeErrorAndLeavesNothing) {
  const fs::path missing = scratch_dir() / "no-such-dir" / "k.json";
  CliRun r = sss_fit("fit --preset skin1 --out " + missing.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(missing));
}
