#include "scene/GltfFile.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

namespace sss::scene {

namespace {

constexpr std::uint32_t kChunkJson = 0x4E4F534Au;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942u;   // "BIN\0"

std::uint32_t le32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

std::variant<std::vector<unsigned char>, std::string> read_file_capped(const std::string& path,
                                                                       std::uint64_t max_bytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return std::string("no such file");
  if (!std::filesystem::is_regular_file(status)) return std::string("is not a regular file");
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return "cannot read its size: " + ec.message();
  if (size == 0) return std::string("is empty");
  if (size > max_bytes)
    return "is " + std::to_string(size) + " bytes, more than the limit of " +
           std::to_string(max_bytes);
  std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) return std::string("cannot open: ") + std::strerror(errno);
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), f.get());
  if (got != bytes.size()) return std::string("changed size or failed while being read");
  if (std::fgetc(f.get()) != EOF) return std::string("grew while being read");
  return bytes;
}

bool has_glb_magic(std::span<const unsigned char> bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

std::variant<GlbLayout, FieldError> parse_glb(std::span<const unsigned char> bytes) {
  const std::uint64_t size = bytes.size();
  if (size < 12)
    return FieldError{"header", "the file is " + std::to_string(size) +
                                    " bytes, shorter than the 12-byte GLB header"};
  if (!has_glb_magic(bytes)) return FieldError{"header.magic", "is not \"glTF\""};
  const std::uint32_t version = le32(bytes.data() + 4);
  if (version != 2)
    return FieldError{"header.version", "must be 2, got " + std::to_string(version)};
  const std::uint64_t length = le32(bytes.data() + 8);
  if (length != size)
    return FieldError{"header.length", "says " + std::to_string(length) +
                                           " bytes but the file has " + std::to_string(size) +
                                           (length > size ? " (truncated?)" : "")};
  GlbLayout layout;
  bool have_json = false, have_bin = false;
  std::uint64_t at = 12;
  for (int chunk = 0; at < length; ++chunk) {
    const std::string name = "chunks[" + std::to_string(chunk) + "]";
    if (length - at < 8)
      return FieldError{name, "header needs 8 bytes but only " + std::to_string(length - at) +
                                  " remain"};
    const std::uint64_t chunk_length = le32(bytes.data() + at);
    const std::uint32_t type = le32(bytes.data() + at + 4);
    at += 8;
    if (chunk_length > length - at)
      return FieldError{name + ".chunkLength",
                        std::to_string(chunk_length) + " bytes run past the end of the file (" +
                            std::to_string(length - at) + " bytes remain)"};
    if (chunk_length % 4 != 0)
      return FieldError{name + ".chunkLength",
                        std::to_string(chunk_length) + " is not a multiple of 4"};
    const unsigned char* payload = bytes.data() + at;
    if (chunk == 0) {
      if (type != kChunkJson) return FieldError{name + ".chunkType", "the first chunk must be JSON"};
      if (chunk_length == 0) return FieldError{name + ".chunkLength", "the JSON chunk is empty"};
      layout.json = std::string_view(reinterpret_cast<const char*>(payload), chunk_length);
      // The padding is spaces; some writers pad with NUL, which JSON parsers refuse.
      while (!layout.json.empty() && (layout.json.back() == '\0' || layout.json.back() == ' '))
        layout.json.remove_suffix(1);
      if (layout.json.empty()) return FieldError{name, "the JSON chunk holds only padding"};
      have_json = true;
    } else if (type == kChunkJson) {
      return FieldError{name + ".chunkType", "a second JSON chunk"};
    } else if (type == kChunkBin) {
      if (chunk != 1 || have_bin)
        return FieldError{name + ".chunkType", "the BIN chunk must be the second chunk, and only one"};
      layout.bin = std::span<const unsigned char>(payload, chunk_length);
      have_bin = true;
    }  // other chunk types: ignored (glTF 2.0 §4.4.3.1)
    at += chunk_length;
  }
  if (!have_json) return FieldError{"chunks[0]", "missing: a GLB needs a JSON chunk"};
  return layout;
}

std::vector<unsigned char> rebuild_glb(const GlbLayout& layout) {
  const std::size_t json_len = (layout.json.size() + 3) / 4 * 4;
  const std::size_t bin_len = (layout.bin.size() + 3) / 4 * 4;
  const std::size_t total = 12 + 8 + json_len + (bin_len ? 8 + bin_len : 0);
  // Sized once and filled in place (GCC 12 warns falsely about inserts after reserve).
  std::vector<unsigned char> out(total, 0);
  const auto put = [&](std::size_t at, std::uint64_t v) {
    for (int i = 0; i < 4; ++i) out[at + std::size_t(i)] = static_cast<unsigned char>(v >> (8 * i));
  };
  std::memcpy(out.data(), "glTF", 4);
  put(4, 2);
  put(8, total);
  put(12, json_len);
  put(16, kChunkJson);
  std::fill(out.begin() + 20, out.begin() + 20 + std::ptrdiff_t(json_len), ' ');
  if (!layout.json.empty()) std::memcpy(out.data() + 20, layout.json.data(), layout.json.size());
  if (bin_len) {
    const std::size_t at = 20 + json_len;
    put(at, bin_len);
    put(at + 4, kChunkBin);
    std::memcpy(out.data() + at + 8, layout.bin.data(), layout.bin.size());
  }
  return out;
}

}  // namespace sss::scene
