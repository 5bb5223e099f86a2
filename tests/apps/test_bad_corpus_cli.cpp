// The malformed-glTF corpus (tests/data/bad/, one file per failure class) through a
// command-line tool: for every file listed in expected.json, sss-reference must exit 2
// (ExitCodes.h: bad input), its stderr must name the file, the object/field and the
// phrase that expected.json gives, and nothing may be written to the output path.
// sss-reference loads the scene before anything else (app/sss-reference/main.cpp), and
// needs no Vulkan. The options make a wrongly accepted file fail fast too (1x1 image, at
// most one irradiance point), so a loader regression shows as a wrong message, not a
// long render.
#ifdef SSS_REFERENCE_EXE

#include "common/CliRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace fs = std::filesystem;

namespace {

const fs::path kBad = fs::path(SSS_SOURCE_DIR) / "tests/data/bad";

// Single quotes for the shell (corpus names are plain, but the checkout path may not be).
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

TEST(BadCorpusCli, SssReferenceExitsTwoNamingFileAndFieldAndWritesNothing) {
  std::ifstream f(kBad / "expected.json");
  const nlohmann::json expected = nlohmann::json::parse(f, nullptr, /*allow_exceptions=*/false);
  ASSERT_TRUE(expected.is_object()) << "cannot read " << kBad / "expected.json";
  ASSERT_GE(expected.size(), 100u);  // the corpus as committed: 160 files

  const fs::path dir = sss::testing::scratch_dir("bad-corpus-cli");
  const fs::path out = dir / "out.exr", png = dir / "out.png";
  const auto start = std::chrono::steady_clock::now();
  for (const auto& [name, want] : expected.items()) {
    SCOPED_TRACE(name);
    const std::string path = (kBad / name).string();
    fs::remove(out);
    fs::remove(png);
    const sss::testing::CliRun r = sss::testing::run_cli(
        SSS_REFERENCE_EXE,
        quoted(path) + " --out " + quoted(out.string()) + " --png " + quoted(png.string()) +
            " --width 1 --height 1 --max-points 1 --threads 1 --quiet",
        dir / "stderr.txt");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find(path + ": "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(want["where"].get<std::string>()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(want["phrase"].get<std::string>()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << out;
    EXPECT_FALSE(fs::exists(png)) << png;
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "  " << expected.size() << " corpus files through sss-reference in " << s << " s\n";
  fs::remove_all(dir);
}

}  // namespace

#endif  // SSS_REFERENCE_EXE
