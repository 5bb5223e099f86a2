#include "FuzzSupport.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace sss::fuzz {

namespace {

class ScratchDir {
 public:
  ScratchDir() {
    std::string base = "/tmp";
    if (const char* t = std::getenv("TMPDIR"); t && *t) base = t;
    if (::access("/dev/shm", W_OK | X_OK) == 0) base = "/dev/shm";  // no disk writes per input
    std::string templ = base + "/sss-fuzz-XXXXXX";
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    if (::mkdtemp(buf.data()) == nullptr) {
      std::perror("sss fuzz: mkdtemp");
      std::abort();
    }
    path_ = buf.data();
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

const ScratchDir& scratch() {
  static const ScratchDir dir;
  return dir;
}

}  // namespace

std::string write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path p = scratch().path() / name;
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  fuzz_check(static_cast<bool>(out), "the scratch file could be written");
  return p.string();
}

void remove_scratch(const std::string& name) {
  std::error_code ec;
  std::filesystem::remove(scratch().path() / name, ec);
}

namespace {
std::uint64_t g_accepted = 0;
}  // namespace

void count_accepted() { ++g_accepted; }
std::uint64_t accepted_inputs() { return g_accepted; }

void fuzz_check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz invariant broken: %s\n", what);
  std::abort();
}

}  // namespace sss::fuzz
