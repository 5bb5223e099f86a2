#include "renderer/image/AtomicFile.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using sss::image::write_file_atomically;
using sss::image::WriteError;

namespace {
// A fresh folder per test.
fs::path dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path p = fs::temp_directory_path() /
               ("sss-atomic-" + std::to_string(::getpid()) + "-" + info->name());
  fs::create_directories(p);
  return p;
}
std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}
int entries() {
  int n = 0;
  for ([[maybe_unused]] auto& e : fs::directory_iterator(dir())) ++n;
  return n;
}
}  // namespace

TEST(AtomicFile, WritesAndReplaces) {
  const fs::path p = dir() / "a.txt";
  write_file_atomically(p.string(), "first");
  EXPECT_EQ(slurp(p), "first");
  write_file_atomically(p.string(), std::string(100000, 'x'));
  EXPECT_EQ(slurp(p).size(), 100000u);
  EXPECT_EQ(entries(), 1);  // no temporary left behind
}

TEST(AtomicFile, FailureNamesThePathAndKeepsTheOldFile) {
  const fs::path p = dir() / "keep.txt";
  write_file_atomically(p.string(), "precious");
  // Renaming a file over a non-empty directory fails after the bytes are written.
  const fs::path blocker = dir() / "blocker";
  fs::create_directories(blocker / "inside");
  try {
    write_file_atomically(blocker.string(), "new");
    FAIL() << "expected a WriteError";
  } catch (const WriteError& e) {
    EXPECT_NE(std::string(e.what()).find(blocker.string()), std::string::npos);
  }
  EXPECT_EQ(slurp(p), "precious");
  EXPECT_TRUE(fs::is_directory(blocker / "inside"));
  EXPECT_EQ(entries(), 2);  // keep.txt and blocker/, no temporaries
}

TEST(AtomicFile, MissingFolderIsAnError) {
  EXPECT_THROW(write_file_atomically((dir() / "nope" / "x.json").string(), "{}"), WriteError);
}
