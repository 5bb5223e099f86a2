// Writing output files so that a failed or interrupted run never leaves a half-written
// file and never destroys an existing one: the bytes go to a temporary file in the same
// folder, are flushed, and the temporary is renamed over the target (rename(2) is atomic
// within one file system). On Linux the temporary is unnamed (O_TMPFILE) until it is
// complete, so even a process killed mid-write (SIGKILL) leaves no file behind.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace sss::image {

struct WriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws WriteError naming the path (and the system's reason) on failure; the target is
// then untouched and no temporary is left behind.
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace sss::image
