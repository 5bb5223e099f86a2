#include "image/AtomicFile.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

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

// A write that fails half-way (the file-size limit RLIMIT_FSIZE makes write(2) fail with
// EFBIG after 4 KiB; it binds root too, unlike folder permissions) names the path, leaves
// the existing file as it was and no temporary behind. In a child process, so the limit
// does not outlive the test.
TEST(AtomicFile, AWriteFailingHalfWayKeepsTheOldFileAndLeavesNoTemporary) {
  const fs::path p = dir() / "keep.bin";
  write_file_atomically(p.string(), "precious");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the signal
    const rlimit limit{4096, 4096};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(3);
    try {
      write_file_atomically(p.string(), std::string(1 << 20, 'x'));
    } catch (const WriteError& e) {
      const std::string what = e.what();
      ::_exit(what.find(p.string()) != std::string::npos && what.find("write failed") != std::string::npos ? 0 : 2);
    }
    ::_exit(1);  // the write succeeded: the limit did not bite
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no failure, 2: the error does not name the path and cause";
  EXPECT_EQ(slurp(p), "precious");
  EXPECT_EQ(entries(), 1);  // no temporary
}

// A process killed (SIGKILL: no handler runs) while it writes leaves the old file as it
// was and nothing else: the bytes go to an unnamed O_TMPFILE that the kernel frees. The
// child writes 64 MiB; the parent waits until the child holds the unnamed file open
// (/proc/PID/fd shows it as "DIR/#INODE (deleted)"), then kills it.
TEST(AtomicFile, AProcessKilledMidWriteLeavesTheOldFileAndNothingElse) {
  const fs::path p = dir() / "keep.bin";
  write_file_atomically(p.string(), "precious");
  const std::string big(std::size_t{64} << 20, 'x');
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    try {
      write_file_atomically(p.string(), big);
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  bool seen_mid_write = false, reaped = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  const fs::path fds = "/proc/" + std::to_string(pid) + "/fd";
  while (!seen_mid_write && std::chrono::steady_clock::now() < deadline) {
    std::error_code ec;
    for (fs::directory_iterator it(fds, ec), end; !ec && it != end; it.increment(ec)) {
      std::error_code ec2;
      const std::string target = fs::read_symlink(it->path(), ec2).string();
      if (!ec2 && target.rfind(dir().string(), 0) == 0 && target != p.string()) seen_mid_write = true;
    }
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {  // finished before we saw it
      reaped = true;
      break;
    }
  }
  if (!reaped) {  // a reaped pid may already belong to another process
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
  }
  const std::string now = slurp(p);
  EXPECT_TRUE(now == "precious" || now.size() == big.size()) << now.size() << " bytes";
  EXPECT_EQ(entries(), 1);  // no temporary, named or not
  std::printf("note: %s; the file afterwards: %s\n",
              seen_mid_write ? "killed after it was seen writing" : "the child finished before it was seen writing",
              now == "precious" ? "the old one" : "the complete new one");
}
