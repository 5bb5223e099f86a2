// Replays every seed and every regression input of the fuzz targets (fuzz/FuzzTargets.h)
// in the ordinary build and under the asan preset, without libFuzzer: a crash that
// scripts/fuzz.sh once found stays fixed. A crash or sanitizer report kills this
// program (ctest reports it, and the last "replay:" line on stderr names the file); an
// uncaught exception fails the test with the file named.
//
// fuzz/regressions/<target>/NAME.pending is a reproducer whose fix has not landed yet: it
// is listed, not run. Rename it (drop ".pending") with the fix.
#include "FuzzSupport.h"
#include "FuzzTargets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::uint8_t> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

// Names the parameter in test output instead of printing its bytes.
void PrintTo(const SssFuzzTarget& t, std::ostream* os) { *os << t.name; }

namespace {

class FuzzReplay : public ::testing::TestWithParam<SssFuzzTarget> {};

TEST_P(FuzzReplay, EverySeedAndRegressionRunsCleanly) {
  const SssFuzzTarget t = GetParam();
  const fs::path root = fs::path(SSS_SOURCE_DIR) / "fuzz";
  const auto seeds = files_in(root / "corpus" / t.name);
  // The seeds are what makes libFuzzer start deep in the parser; an empty folder means
  // they were lost.
  ASSERT_FALSE(seeds.empty()) << "no seeds in " << (root / "corpus" / t.name);
  // Every seed is a valid input (fuzz/README.md): it must be accepted, or libFuzzer
  // would start at the first check instead of deep in the parser.
  for (const auto& p : seeds) {
    const auto bytes = read_bytes(p);
    const std::uint64_t before = sss::fuzz::accepted_inputs();
    std::fprintf(stderr, "seed: %s (%zu bytes)\n", p.c_str(), bytes.size());
    EXPECT_EQ(t.run(bytes.data(), bytes.size()), 0) << p;
    EXPECT_GT(sss::fuzz::accepted_inputs(), before) << p << " is a seed but was rejected";
  }
  std::vector<fs::path> inputs;
  for (const auto& p : files_in(root / "regressions" / t.name)) {
    if (p.extension() == ".pending") {
      std::printf("pending (not replayed until fixed): %s\n", p.c_str());
      continue;
    }
    inputs.push_back(p);
  }
  // Reproducers: any outcome but a crash, a sanitizer report or an exception is right.
  for (const auto& p : inputs) {
    const auto bytes = read_bytes(p);
    std::fprintf(stderr, "replay: %s (%zu bytes)\n", p.c_str(), bytes.size());
    int rc = -1;
    try {
      rc = t.run(bytes.data(), bytes.size());
    } catch (const std::exception& e) {
      ADD_FAILURE() << p << ": uncaught exception: " << e.what();
      continue;
    } catch (...) {
      ADD_FAILURE() << p << ": uncaught non-standard exception";
      continue;
    }
    // libFuzzer reserves non-zero returns; every target returns 0.
    EXPECT_EQ(rc, 0) << p;
  }
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay, ::testing::ValuesIn(kSssFuzzTargets),
                         [](const ::testing::TestParamInfo<SssFuzzTarget>& param) {
                           return std::string(param.param.name);
                         });

}  // namespace
