// Helpers for the fuzz targets: a private scratch folder for the inputs that the code
// under test only reads from a path, and a check that aborts with a message.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace sss::fuzz {

// Writes the bytes to <scratch>/<name> and returns the path. The scratch folder is made
// once per process (mkdtemp under /dev/shm when it is writable, else $TMPDIR or /tmp),
// holds nothing else, so that relative URIs in a fuzzed glTF find nothing outside it,
// and is removed at exit.
std::string write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size);
// Removes <scratch>/<name>, so that the next input cannot read this one.
void remove_scratch(const std::string& name);

// Prints "fuzz invariant broken: WHAT" and aborts (a crash for libFuzzer and for the
// replay test) when `ok` is false.
void fuzz_check(bool ok, const char* what);

// Counts inputs that the code under test accepted (a Scene, a material, a medium, an
// image). The replay test checks with it that every seed in fuzz/corpus/ is a valid
// input, i.e. that libFuzzer starts past the first check.
void count_accepted();
std::uint64_t accepted_inputs();

}  // namespace sss::fuzz
