// Running an executable under test: its exit code, stdout and stderr. Shared by the
// app tests (sss-fit, sss-compare, sss-reference) and the viewer tests.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace sss::testing {

struct CliRun {
  int code = -1;  // the exit status; -1 when the process did not exit normally
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs `exe args` through the shell; stderr goes through `stderr_file`, which is removed.
inline CliRun run_cli(const std::string& exe, const std::string& args,
                      const std::filesystem::path& stderr_file) {
  const std::string cmd = exe + " " + args + " 2>" + stderr_file.string();
  CliRun r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = slurp(stderr_file);
  std::filesystem::remove(stderr_file);
  return r;
}

// Runs a shell command line; `out` holds stdout and stderr together (2>&1).
inline CliRun run_shell(const std::string& command) {
  CliRun r;
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A folder of its own for a test program, under the system's temporary folder.
inline std::filesystem::path scratch_dir(const std::string& name) {
  std::filesystem::path d =
      std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace sss::testing
