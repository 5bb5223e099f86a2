// Every documented sss-fit command and every documented error (DESIGN.md §4): exit code
// 0 on success, 2 for bad usage or input with the field named on stderr, 1 for runtime
// failures; --json prints exactly one JSON document.
#include "common/CliRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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
        BadInput{"fit --subsurface-color 0.5,1,0.5 --subsurface-radius 1", "--subsurface-color[1]"},
        BadInput{"fit --subsurface-color 0.5 --subsurface-radius 0", "--subsurface-radius"},
        BadInput{"fit --subsurface-color 0.5 --subsurface-radius 1 --subsurface-radius-scale 1,0,1",
                 "--subsurface-radius-scale[1]"},
        BadInput{"fit --subsurface-color 0.5 --subsurface-radius 1 --eta 3", "--eta"},
        BadInput{"fit --subsurface-color 0.5 --subsurface-radius 1 --g 1", "--g"},
        BadInput{"fit --subsurface-color 0.5", "--subsurface-radius: is required"},
        BadInput{"fit --subsurface-color 0.5 --subsurface-radius 1,1,1 --subsurface-scale 0", "--subsurface-scale"},
        BadInput{"fit --subsurface-color 0.5 --subsurface-radius 1 --albedo-inversion exact", "--albedo-inversion"},
        BadInput{"fit --preset skin1 --albedo-inversion model", "applies only to --subsurface-color"},
        BadInput{"fit --preset skin1 --subsurface-color 0.5", "exclude each other"},
        BadInput{"fit --preset skin1 --bogus", "bogus"}));

TEST(SssFit, UnwritableOutputIsARuntimeErrorAndLeavesNothing) {
  const fs::path missing = scratch_dir() / "no-such-dir" / "k.json";
  CliRun r = sss_fit("fit --preset skin1 --out " + missing.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(missing));
}

// --layers FILE.json (issue 19): a stack of layers instead of MEDIUM, model layered.
namespace {

fs::path write_layers(const std::string& name, const std::string& text) {
  const fs::path p = scratch_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// A dense 0.5 mm top layer (reduced mean free path 0.03-0.05 mm) over skin1, semi-infinite
// or 3 mm thick.
const char* const kOverSkin = R"({"layers": [
  {"sigma_a": [0.2, 0.3, 0.5], "sigma_s": [20, 25, 30], "g": 0, "eta": 1.3, "thickness_mm": 0.5},
  {"preset": "skin1"}]})";
const char* const kFiniteBottom = R"({"layers": [
  {"sigma_a": [0.2, 0.3, 0.5], "sigma_s": 25, "thickness_mm": 0.5},
  {"preset": "skin1", "thickness_mm": 3}]})";

}  // namespace

TEST(SssFitLayers, HelpDescribesLayers) {
  for (const char* cmd : {"profile", "fit", "validate"}) {
    CliRun r = sss_fit(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.out.find("--layers FILE.json"), std::string::npos) << cmd << r.out;
    EXPECT_NE(r.out.find("thickness_mm"), std::string::npos) << cmd;
  }
}

TEST(SssFitLayers, ProfilePrintsRAndTOnlyForAFiniteBottom) {
  const fs::path semi = write_layers("over-skin.json", kOverSkin);
  CliRun r = sss_fit("profile --layers " + semi.string() + " --radii 0.1:4:5 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto doc = parse_only_json(r.out);
  EXPECT_EQ(doc["model"], "layered");
  ASSERT_EQ(doc["R"].size(), 5u);
  EXPECT_EQ(doc["R"][0].size(), 3u);
  EXPECT_GT(doc["R"][0][0].get<double>(), doc["R"][4][0].get<double>());
  EXPECT_FALSE(doc.contains("T"));  // a semi-infinite base has no far face
  EXPECT_FALSE(doc.contains("total_transmittance"));
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(doc["total_reflectance"][c].get<double>(), 0.0);
    EXPECT_LT(doc["total_reflectance"][c].get<double>(), 1.0);
  }
  // The stack as read, the preset expanded, the semi-infinite base without a thickness.
  ASSERT_EQ(doc["layers"].size(), 2u);
  EXPECT_EQ(doc["layers"][0]["thickness_mm"].get<double>(), 0.5);
  EXPECT_EQ(doc["layers"][0]["sigma_s"][1].get<double>(), 25.0);
  EXPECT_EQ(doc["layers"][1]["sigma_a"][0].get<double>(), 0.032);  // skin1
  EXPECT_FALSE(doc["layers"][1].contains("thickness_mm"));

  // --model layered is what --layers implies: the same document.
  CliRun named = sss_fit("profile --layers " + semi.string() + " --model layered --radii 0.1:4:5 --json");
  ASSERT_EQ(named.code, 0) << named.err;
  EXPECT_EQ(named.out, r.out);

  const fs::path finite = write_layers("finite-bottom.json", kFiniteBottom);
  CliRun f = sss_fit("profile --layers " + finite.string() + " --radii 0:4:3 --json");
  ASSERT_EQ(f.code, 0) << f.err;
  auto fdoc = parse_only_json(f.out);
  ASSERT_TRUE(fdoc.contains("T"));
  ASSERT_EQ(fdoc["T"].size(), 3u);
  EXPECT_EQ(fdoc["T"][0].size(), 3u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(fdoc["T"][0][c].get<double>(), 0.0);
    EXPECT_GT(fdoc["total_transmittance"][c].get<double>(), 0.0);
  }

  // Text: the header names the model, one line per radius, T columns for the finite bottom.
  CliRun t = sss_fit("profile --layers " + finite.string() + " --radii 0:4:3");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("# model layered"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("T_r T_g T_b"), std::string::npos) << t.out;
  std::istringstream lines(t.out);
  int rows = 0;
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line[0] != '#') {
      ++rows;
      std::istringstream fields(line);
      int n = 0;
      for (std::string x; fields >> x;) ++n;
      EXPECT_EQ(n, 7) << line;  // r, R x3, T x3
    }
  EXPECT_EQ(rows, 3);
}

TEST(SssFitLayers, FitFitsTheLayeredProfile) {
  const fs::path semi = write_layers("over-skin.json", kOverSkin);
  CliRun p = sss_fit("profile --layers " + semi.string() + " --radii 0:1:2 --json");
  ASSERT_EQ(p.code, 0) << p.err;
  const auto profile_total = parse_only_json(p.out)["total_reflectance"];

  const fs::path out = scratch_dir() / "layered-kernel.json";
  CliRun r = sss_fit("fit --layers " + semi.string() + " --gaussians 4 --json --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  auto doc = parse_only_json(r.out);
  EXPECT_EQ(doc["model"], "layered");
  EXPECT_NE(doc["medium"].get<std::string>().find("over-skin.json"), std::string::npos);
  ASSERT_EQ(doc["variances_mm2"].size(), 4u);
  for (int c = 0; c < 3; ++c) {
    double sum = 0;
    for (auto& w : doc["weights"]) sum += w[c].get<double>();
    EXPECT_NEAR(sum, doc["total_reflectance"][c].get<double>(), 1e-9);
    // The Gaussians carry the layered profile's energy (the fit samples it to its
    // support radius; the closed total and the sampled one differ by the quadrature).
    EXPECT_NEAR(sum, profile_total[c].get<double>(), 0.01 * profile_total[c].get<double>()) << c;
  }
  EXPECT_EQ(nlohmann::json::parse(slurp(out)), doc);
}

TEST(SssFitLayers, ValidateComparesWithTheLayeredWalk) {
  const fs::path finite = write_layers("finite-bottom.json", kFiniteBottom);
  CliRun r = sss_fit("validate --layers " + finite.string() + " --photons 20000 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto doc = parse_only_json(r.out);
  ASSERT_EQ(doc["models"].size(), 1u);
  EXPECT_EQ(doc["models"][0]["model"], "layered");
  EXPECT_EQ(doc["range_mm"], nlohmann::json::array({0.25, 8.0}));
  EXPECT_EQ(doc["layers"].size(), 2u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(doc["monte_carlo"]["total_transmittance"][c].get<double>(), 0.0) << c;
    // The same stack on both sides: the totals agree (0.6% or better measured; the walk's
    // standard error is 0.4% of them at 20000 photons).
    EXPECT_LT(std::fabs(doc["models"][0]["total_relative_error"][c].get<double>()), 0.03) << c;
  }
  CliRun t = sss_fit("validate --layers " + finite.string() + " --photons 20000");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("layered"), std::string::npos);
  EXPECT_NE(t.out.find("0.25..8 mm"), std::string::npos) << t.out;
}

TEST(SssFitLayers, UsageErrorsNameBothOptionsOrTheFile) {
  const std::string good = write_layers("over-skin.json", kOverSkin).string();
  const std::string malformed = write_layers("malformed.json", "{\"layers\": [\n  {\"preset\": \"skin1\",}\n]}").string();
  const std::string bad_layer = write_layers("bad-layer.json", R"({"layers": [
      {"sigma_a": 0.1, "sigma_s": 10, "thickness_mm": 1},
      {"sigma_a": [0.1, 0.1, "x"], "sigma_s": 10}]})").string();
  const std::string missing = (scratch_dir() / "no-such-layers.json").string();
  struct Case {
    std::string args;
    std::vector<std::string> expected;  // every piece must be on stderr
  };
  const std::vector<Case> cases = {
      {"profile --layers " + good + " --model dipole --radii 0:1:2", {"--model", "--layers", "dipole"}},
      {"fit --layers " + good + " --model mc-table", {"--model", "--layers", "mc-table"}},
      {"fit --layers " + good + " --preset skin1", {"--layers", "--preset"}},
      {"fit --layers " + good + " --sigma-a 0.1 --sigma-s 1", {"--layers", "--sigma-a"}},
      {"validate --layers " + good + " --thickness 2", {"--layers", "--thickness"}},
      {"profile --layers " + good + " --eta 1.4 --radii 0:1:2", {"--layers", "--eta"}},
      {"fit --model layered --preset skin1", {"--model", "--layers"}},
      {"fit --layers " + missing, {missing, "cannot be opened"}},
      {"validate --layers " + missing, {missing}},
      {"fit --layers " + malformed, {malformed, "not valid JSON", "line 2"}},
      {"profile --layers " + bad_layer + " --radii 0:1:2", {bad_layer, "layers[1].sigma_a[2]"}},
  };
  for (const Case& c : cases) {
    CliRun r = sss_fit(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("sss-fit: error: ", 0), 0u) << c.args << "\n" << r.err;
    for (const std::string& piece : c.expected)
      EXPECT_NE(r.err.find(piece), std::string::npos) << c.args << ": no '" << piece << "' in\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args << "\n" << r.out;
  }
}

TEST(SssFitLayers, AnErrorLeavesNoOutputFile) {
  const std::string good = write_layers("over-skin.json", kOverSkin).string();
  const std::string malformed = write_layers("malformed.json", "{\"layers\": [").string();
  // Valid for the parser, refused by the layered model: a 0.1 mm layer whose reduced mean
  // free path is 0.9 mm.
  const std::string thin = write_layers("thin.json", R"({"layers": [
      {"sigma_a": 0.1, "sigma_s": 1, "thickness_mm": 0.1}, {"preset": "skin1"}]})").string();
  const fs::path out = scratch_dir() / "never.json", plot = scratch_dir() / "never.svg";
  for (const std::string& args :
       {"--layers " + malformed, "--layers " + good + " --model dipole",
        "--layers " + good + " --preset skin1", "--layers " + thin,
        "--layers " + (scratch_dir() / "absent.json").string()}) {
    CliRun r = sss_fit("fit " + args + " --out " + out.string() + " --plot " + plot.string());
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << args;
    EXPECT_FALSE(fs::exists(plot)) << args;
  }
  for (auto& e : fs::directory_iterator(scratch_dir()))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

// Issue 20 part 5: the guards a new user meets first.
namespace {

// "sigma_a a,b,c sigma_s d,e,f" after "=" in the fit's header line.
std::pair<std::string, std::string> derived_coefficients(const std::string& out) {
  const auto a = out.find("= sigma_a ");
  if (a == std::string::npos) return {};
  std::istringstream in(out.substr(a + 10));
  std::string sa, word, ss;
  in >> sa >> word >> ss;
  return {sa, ss};
}

}  // namespace

TEST(SssFitGuards, FileNamesMustSayTheFormat) {
  const fs::path png = scratch_dir() / "k.png", txt = scratch_dir() / "k.txt";
  const CliRun p = sss_fit("fit --preset marble --plot " + png.string());
  EXPECT_EQ(p.code, 2);
  EXPECT_NE(p.err.find("--plot: writes an SVG plot, name it .svg"), std::string::npos) << p.err;
  EXPECT_FALSE(fs::exists(png));
  const CliRun t = sss_fit("fit --preset marble --out " + txt.string());
  EXPECT_EQ(t.code, 2);
  EXPECT_NE(t.err.find("--out: writes a JSON kernel (.json) or a C header"), std::string::npos) << t.err;
  EXPECT_FALSE(fs::exists(txt));
}

// σ typed in m^-1 (skin1's 0.032 mm^-1 as 32) fits nanometre Gaussians: warned. The same
// medium in mm^-1, and every preset's (23-230 µm narrowest), is not.
TEST(SssFitGuards, WrongUnitsAreWarnedAbout) {
  const CliRun m = sss_fit("fit --sigma-a 32,170,480 --sigma-s 740,880,1010");
  EXPECT_EQ(m.code, 0) << m.err;
  EXPECT_NE(m.err.find("under 1 µm: are σ given in mm^-1"), std::string::npos) << m.err;
  const CliRun far = sss_fit("fit --color 0.5 --mfp 2000");
  EXPECT_EQ(far.code, 0) << far.err;
  EXPECT_NE(far.err.find("over a metre"), std::string::npos) << far.err;
  for (const char* preset : {"cream", "skin1", "chicken2"}) {
    const CliRun ok = sss_fit(std::string("fit --preset ") + preset);
    EXPECT_EQ(ok.code, 0) << ok.err;
    EXPECT_EQ(ok.err.find("warning"), std::string::npos) << preset << ": " << ok.err;
  }
}

// Artist mode prints the coefficients it derived; fitting those coefficients directly
// gives back the colour as total reflectance (an independent path: the forward model, not
// the inversion). The coefficients are printed to 6 significant digits, a relative change
// of 5e-6 at most, which moves a total reflectance by less than 1e-5; 1e-4 is allowed.
TEST(SssFitGuards, ArtistModePrintsTheCoefficientsItDerived) {
  const CliRun a = sss_fit("fit --color 0.8,0.5,0.3 --mfp 1,0.5,0.25");
  ASSERT_EQ(a.code, 0) << a.err;
  const auto [sa, ss] = derived_coefficients(a.out);
  ASSERT_FALSE(sa.empty()) << a.out;
  const CliRun c = sss_fit("fit --json --sigma-a " + sa + " --sigma-s " + ss);
  ASSERT_EQ(c.code, 0) << c.err;
  const auto doc = parse_only_json(c.out);
  const double color[3] = {0.8, 0.5, 0.3};
  for (int ch = 0; ch < 3; ++ch)
    EXPECT_NEAR(doc["total_reflectance"][ch].get<double>(), color[ch], 1e-4) << ch;
}

// OpenPBR's parameters on the command line are the same medium as extras.sss.openpbr
// (tested against the spec in test_openpbr.cpp): σt = 1 / (radius × radius_scale), and
// Standard Surface's radius colour × scale the same mean free paths. The printed
// coefficients, given back as --sigma-a/--sigma-s, fit the same profile.
TEST(SssFitGuards, OpenPbrAndStandardSurfaceOptions) {
  const CliRun a = sss_fit("fit --subsurface-color 0.671,0.505,0.371 --subsurface-radius 2 "
                           "--subsurface-radius-scale 0.482,0.169,0.109 --eta 1.4");
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_NE(a.out.find("OpenPBR subsurface"), std::string::npos) << a.out;
  const auto [sa, ss] = derived_coefficients(a.out);
  ASSERT_FALSE(sa.empty()) << a.out;
  double a3[3], s3[3];
  ASSERT_EQ(std::sscanf(sa.c_str(), "%lf,%lf,%lf", &a3[0], &a3[1], &a3[2]), 3) << sa;
  ASSERT_EQ(std::sscanf(ss.c_str(), "%lf,%lf,%lf", &s3[0], &s3[1], &s3[2]), 3) << ss;
  const double scale[3] = {0.482, 0.169, 0.109};
  for (int c = 0; c < 3; ++c)  // printed to 6 digits
    EXPECT_NEAR((a3[c] + s3[c]) * 2.0 * scale[c], 1.0, 2e-5) << c;
  const CliRun b = sss_fit("fit --subsurface-color 0.671,0.505,0.371 --subsurface-radius 0.964,0.338,0.218 "
                           "--eta 1.4");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NE(b.out.find("Standard Surface subsurface"), std::string::npos) << b.out;
  EXPECT_EQ(derived_coefficients(b.out), derived_coefficients(a.out));
  // The project's inversion scatters more behind the same boundary.
  const CliRun m = sss_fit("fit --subsurface-color 0.671,0.505,0.371 --subsurface-radius 2 "
                           "--subsurface-radius-scale 0.482,0.169,0.109 --eta 1.4 --albedo-inversion model --json");
  ASSERT_EQ(m.code, 0) << m.err;
  const auto doc = parse_only_json(m.out);
  const double color[3] = {0.671, 0.505, 0.371};
  for (int ch = 0; ch < 3; ++ch)  // mc-table's total, inverted to 1e-9
    EXPECT_NEAR(doc["total_reflectance"][ch].get<double>(), color[ch], 1e-4) << ch;
}

// sss-fit export: each format writes its files (both or none), reports the Burley fit's
// error, and refuses a file name that does not say the format. The files' content is
// tested in tests/profiles/test_engine_profiles.cpp.
TEST(SssFitExport, EveryFormatWritesItsFilesAndReportsTheFit) {
  const fs::path dir = scratch_dir() / "export";
  fs::create_directories(dir);
  const CliRun h = sss_fit("export --format hdrp --preset skin1 --out " + (dir / "Skin.asset").string());
  ASSERT_EQ(h.code, 0) << h.err;
  EXPECT_TRUE(fs::exists(dir / "Skin.asset"));
  EXPECT_TRUE(fs::exists(dir / "Skin.asset.meta"));
  EXPECT_NE(h.out.find("relative L2 error"), std::string::npos) << h.out;
  EXPECT_NE(slurp(dir / "Skin.asset").find("m_Name: Skin\n"), std::string::npos);

  const CliRun u = sss_fit("export --format unreal --json --name Wax --preset marble --out " +
                           (dir / "wax.json").string());
  ASSERT_EQ(u.code, 0) << u.err;
  const auto doc = parse_only_json(u.out);
  EXPECT_EQ(doc["files"].size(), 2u);
  EXPECT_EQ(doc["burley_relative_error"].size(), 3u);
  EXPECT_TRUE(fs::exists(dir / "wax.py"));
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "wax.json"))["name"], "Wax");

  for (const char* f : {"kernel-json", "c-header"}) {
    const fs::path out = dir / (std::string("k") + (f[0] == 'k' ? ".json" : ".h"));
    const CliRun k = sss_fit(std::string("export --format ") + f + " --preset skin1 --out " + out.string());
    ASSERT_EQ(k.code, 0) << k.err;
    EXPECT_TRUE(fs::exists(out)) << f;
  }
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"export --format hdrp --preset skin1 --out x.json", "NAME.asset"},
           {"export --format unreal --preset skin1 --out x.asset", "NAME.json"},
           {"export --format kernel-json --preset skin1 --out x.h", ".json"},
           {"export --format fbx --preset skin1 --out x.fbx", "expected hdrp, unreal"},
           {"export --format hdrp --preset skin1 --world-scale 0 --out x.asset", "--world-scale"},
           {"export --format hdrp --preset skin1", "--out"}}) {
    const CliRun e = sss_fit(args);
    EXPECT_EQ(e.code, 2) << args;
    EXPECT_NE(e.err.find(expected), std::string::npos) << args << "\n" << e.err;
  }
  // An unwritable second file leaves neither.
  const fs::path blocked = dir / "Blocked.asset.meta";
  fs::create_directories(blocked);  // a directory where the .meta would go
  const CliRun b = sss_fit("export --format hdrp --preset skin1 --out " + (dir / "Blocked.asset").string());
  EXPECT_EQ(b.code, 1) << b.err;
  EXPECT_FALSE(fs::exists(dir / "Blocked.asset"));
  fs::remove_all(dir);
}

TEST(SssFitGuards, TyposGetTheNearestOptionOrCommand) {
  const CliRun o = sss_fit("fit --preset marble --gaussian 4");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("did you mean '--gaussians' for '--gaussian'?"), std::string::npos) << o.err;
  const CliRun c = sss_fit("fitt --preset marble");
  EXPECT_EQ(c.code, 2);
  EXPECT_NE(c.err.find("did you mean 'fit' for 'fitt'?"), std::string::npos) << c.err;
  const CliRun far = sss_fit("fit --preset marble --zzzzzz 1");
  EXPECT_EQ(far.code, 2);
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;  // nothing near
}

// Not a terminal (this test's pipe, a CI log): a progress line every 10%.
TEST(SssFitGuards, MonteCarloShowsProgressInALog) {
  const fs::path svg = scratch_dir() / "progress.svg";
  const CliRun r = sss_fit("fit --preset skin1 --plot " + svg.string() + " --plot-mc --photons 20000");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* line : {"sss-fit: Monte Carlo 0%", "sss-fit: Monte Carlo 50%", "sss-fit: Monte Carlo 100%"})
    EXPECT_NE(r.err.find(line), std::string::npos) << line << "\n" << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
}
