// GltfUri: what a glTF file may point at. Only two kinds of URI are accepted:
//   - a data URI, "data:<type>;base64,<payload>", with a type that fits its use and
//     a payload that is strict base64 (alphabet, padding, length) of the right size;
//   - a relative path below the glTF file's folder: no scheme, no absolute path, no
//     backslash, no ".." segment, no NUL, checked both as written and percent-decoded
//     (tinygltf percent-decodes before it opens a file).
// External files are then read only through FileSandbox, which tinygltf gets as its
// file-system callbacks: no path expansion, nothing outside the folder, a size cap per
// file and a byte budget for all of them. Internal to the loader.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace sss::scene {

enum class UriUse { Buffer, Image };

// nullopt when the URI is acceptable, else why not. For a buffer's data URI,
// `expected_bytes` is its byteLength, which the payload must decode to.
std::optional<std::string> check_uri(std::string_view uri, UriUse use,
                                     std::optional<std::uint64_t> expected_bytes = std::nullopt);

// The decoded size of strict base64 text, or nullopt if it is not strict base64.
std::optional<std::uint64_t> base64_decoded_size(std::string_view text);

// A file URI as tinygltf 2.7.0 decodes it before opening the file (dlib::urldecode:
// "%XX" escapes and '+' as a space). `uri` must have passed check_uri.
std::string decode_file_uri(std::string_view uri);

struct FileSandbox {
  std::filesystem::path root;  // absolute folder of the glTF file
  std::uint64_t max_file_bytes = 0;
  std::uint64_t bytes_left = 0;  // shared by every external file of one load
  bool contains(const std::string& path) const;  // lexically, without touching the disk
  // contains(path), and the file the path resolves to (symbolic links followed) lies
  // below the folder the root resolves to.
  bool resolves_inside(const std::string& path) const;
};

tinygltf::FsCallbacks sandbox_callbacks(FileSandbox* sandbox);

}  // namespace sss::scene
