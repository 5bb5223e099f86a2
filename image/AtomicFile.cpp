#include "image/AtomicFile.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sss::image {

namespace {

std::string reason() { return std::strerror(errno); }

// Writes all of `bytes` to `fd`; false with errno set on failure.
bool write_all(int fd, std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

// Renames `tmp` over `path`; on failure removes `tmp` and throws.
void rename_into_place(const std::string& tmp, const std::string& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = reason();
    ::unlink(tmp.c_str());
    throw WriteError(path + ": cannot rename the finished file into place: " + why);
  }
}

// The portable way: a named temporary (mkstemp) written, flushed and renamed. A process
// killed mid-write (SIGKILL) leaves the hidden ".NAME.tmp-XXXXXX" behind, never NAME.
void write_with_named_temporary(const std::string& path, const std::filesystem::path& dir,
                                const std::string& leaf, std::string_view bytes) {
  std::string tmpl = (dir / ("." + leaf + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw WriteError(path + ": cannot create a temporary file in " + dir.string() + ": " + reason());
  auto fail = [&](const std::string& what) {
    const std::string why = reason();
    ::close(fd);
    ::unlink(tmpl.c_str());
    throw WriteError(path + ": " + what + ": " + why);
  };
  if (!write_all(fd, bytes)) fail("write failed");
  if (::fsync(fd) != 0) fail("fsync failed");
  // mkstemp creates 0600; give the file the permissions a plain create would have.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  if (::fchmod(fd, 0666 & ~mask) != 0) fail("chmod failed");
  if (::close(fd) != 0) {
    const std::string why = reason();
    ::unlink(tmpl.c_str());
    throw WriteError(path + ": close failed: " + why);
  }
  rename_into_place(tmpl, path);
}

}  // namespace

void write_file_atomically(const std::string& path, std::string_view bytes) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.filename().empty()) throw WriteError(path + ": not a file name");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string leaf = target.filename().string();

  // Linux: an unnamed file in the folder (O_TMPFILE, open(2)), named only once it is
  // complete and flushed. A process killed while writing (SIGKILL, OOM, power) then
  // leaves nothing at all: the kernel frees the unnamed inode. File systems without
  // O_TMPFILE answer EOPNOTSUPP (or EISDIR/EINVAL on old kernels): the named way.
  const int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);  // umask applies
  if (fd < 0) {
    if (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL)
      return write_with_named_temporary(path, dir, leaf, bytes);
    throw WriteError(path + ": cannot create a temporary file in " + dir.string() + ": " + reason());
  }
  auto fail = [&](const std::string& what) {
    const std::string why = reason();
    ::close(fd);  // the unnamed file goes with its last descriptor
    throw WriteError(path + ": " + what + ": " + why);
  };
  if (!write_all(fd, bytes)) fail("write failed");
  if (::fsync(fd) != 0) fail("fsync failed");
  // Give the finished file a hidden unique name, then rename it over the target (link(2)
  // cannot replace an existing file). Only this last step, with no data left to write,
  // can leave the hidden name behind if the process dies between the two calls.
  static std::atomic<unsigned> counter{0};
  const std::string proc = "/proc/self/fd/" + std::to_string(fd);
  std::string tmp;
  for (int attempt = 0;; ++attempt) {
    tmp = (dir / ("." + leaf + ".tmp-" + std::to_string(::getpid()) + "-" +
                  std::to_string(counter.fetch_add(1)))).string();
    if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, tmp.c_str(), AT_SYMLINK_FOLLOW) == 0) break;
    if (errno == EEXIST && attempt < 100) continue;
    if (errno == ENOENT || errno == EPERM || errno == EOPNOTSUPP) {
      // No /proc (or a file system that refuses the link): write the bytes the named way.
      ::close(fd);
      return write_with_named_temporary(path, dir, leaf, bytes);
    }
    fail("cannot name the finished file");
  }
  if (::close(fd) != 0) {
    const std::string why = reason();
    ::unlink(tmp.c_str());
    throw WriteError(path + ": close failed: " + why);
  }
  rename_into_place(tmp, path);
}

}  // namespace sss::image
