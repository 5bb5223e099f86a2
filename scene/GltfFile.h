// GltfFile: the bytes of a glTF file, read with a size cap, and the GLB container
// checked before anything parses it (glTF 2.0 §4.4: 12-byte header, then 8-byte chunk
// headers; chunk 0 is JSON, an optional chunk 1 is BIN; every chunk 4-byte aligned).
// Internal to the loader.
#pragma once

#include "profiles/Medium.h"  // sss::FieldError

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace sss::scene {

// The whole file, or a message: not a regular file, unreadable, empty, or larger than
// max_bytes (checked before reading, and again while reading).
std::variant<std::vector<unsigned char>, std::string> read_file_capped(const std::string& path,
                                                                       std::uint64_t max_bytes);

bool has_glb_magic(std::span<const unsigned char> bytes);

// Views into the bytes given to parse_glb(): they must outlive it.
struct GlbLayout {
  std::string_view json;               // chunk 0 payload, trailing padding removed
  std::span<const unsigned char> bin;  // chunk 1 payload; empty when there is none
};

// Checks magic, version 2, the declared length against the real size, every chunk
// header and length (64-bit arithmetic), 4-byte alignment, JSON first, BIN second and
// at most once. Unknown chunks after them are skipped, as the spec asks. Fields are
// named "header.magic", "chunks[1].chunkLength", ...
std::variant<GlbLayout, FieldError> parse_glb(std::span<const unsigned char> bytes);

// A canonical GLB of the same JSON and BIN: what tinygltf is given, so that it sees
// exactly the chunks checked above (space padding, no unknown chunks).
std::vector<unsigned char> rebuild_glb(const GlbLayout& layout);

}  // namespace sss::scene
