// GltfTestWriter: builds small glTF files for the loader tests: a JSON document plus one
// binary buffer, written as .gltf (data URI or external .bin) or .glb.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace sss::scene::testing {

inline std::string base64(const std::vector<unsigned char>& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::uint32_t n = std::uint32_t(in[i]) << 16 |
                            (i + 1 < in.size() ? std::uint32_t(in[i + 1]) << 8 : 0u) |
                            (i + 2 < in.size() ? std::uint32_t(in[i + 2]) : 0u);
    out += k[(n >> 18) & 63];
    out += k[(n >> 12) & 63];
    out += i + 1 < in.size() ? k[(n >> 6) & 63] : '=';
    out += i + 2 < in.size() ? k[n & 63] : '=';
  }
  return out;
}

inline void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& b) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

class GltfTestWriter {
 public:
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
  std::vector<unsigned char> bin;

  // A buffer view over new bytes (4-byte aligned), returning its index.
  int view(const void* data, std::size_t bytes, int stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    const std::size_t offset = bin.size();
    bin.resize(offset + bytes);
    std::memcpy(bin.data() + offset, data, bytes);
    nlohmann::json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
    if (stride) v["byteStride"] = stride;
    return push("bufferViews", v);
  }
  int accessor(int view_index, int component_type, std::size_t count, const char* type,
               bool normalized = false) {
    nlohmann::json a = {{"bufferView", view_index}, {"componentType", component_type},
                        {"count", count}, {"type", type}};
    if (normalized) a["normalized"] = true;
    return push("accessors", a);
  }
  int floats(const std::vector<float>& v, const char* type, int components) {
    return accessor(view(v.data(), v.size() * 4), 5126, v.size() / std::size_t(components), type);
  }
  template <typename T>
  int indices(const std::vector<T>& v) {
    const int ct = sizeof(T) == 1 ? 5121 : sizeof(T) == 2 ? 5123 : 5125;
    return accessor(view(v.data(), v.size() * sizeof(T)), ct, v.size(), "SCALAR");
  }
  int push(const char* array, nlohmann::json value) {
    doc[array].push_back(std::move(value));
    return int(doc[array].size()) - 1;
  }

  void write_gltf(const std::filesystem::path& path) {
    nlohmann::json d = doc;
    d["buffers"] = {{{"byteLength", bin.size()},
                     {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    std::ofstream(path) << d.dump(1);
  }
  void write_gltf_external(const std::filesystem::path& path, const std::string& bin_uri) {
    nlohmann::json d = doc;
    d["buffers"] = {{{"byteLength", bin.size()}, {"uri", bin_uri}}};
    std::ofstream(path) << d.dump(1);
    write_bytes(path.parent_path() / bin_uri, bin);
  }
  // `pad` fills the JSON chunk to 4 bytes (the spec says ' '); `extra_chunk` appends a
  // chunk of an unknown type, which readers must skip.
  void write_glb(const std::filesystem::path& path, char pad = ' ', bool extra_chunk = false) {
    nlohmann::json d = doc;
    d["buffers"] = {{{"byteLength", bin.size()}}};
    std::string json = d.dump();
    if (json.size() % 4 == 0) json += ' ';  // make room for at least one padding byte
    while (json.size() % 4) json += pad;
    std::vector<unsigned char> b = bin;
    while (b.size() % 4) b.push_back(0);
    // Streamed piece by piece (GCC 12 warns falsely about vector inserts here).
    std::ofstream f(path, std::ios::binary);
    const auto u32 = [&](std::uint32_t v) {
      const char le[4] = {char(v & 0xFF), char((v >> 8) & 0xFF), char((v >> 16) & 0xFF), char(v >> 24)};
      f.write(le, 4);
    };
    f.write("glTF", 4);
    u32(2);
    u32(std::uint32_t(12 + 8 + json.size() + 8 + b.size() + (extra_chunk ? 12 : 0)));
    u32(std::uint32_t(json.size()));
    u32(0x4E4F534Au);
    f.write(json.data(), std::streamsize(json.size()));
    u32(std::uint32_t(b.size()));
    u32(0x004E4942u);
    f.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
    if (extra_chunk) {
      u32(4);
      u32(0x12345678u);
      u32(0xFFFFFFFFu);
    }
  }
};

// A fresh, empty folder for one test's files, removed when the test ends.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("sss_scene_test_" + std::to_string(::getpid()) + "_" + name)) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace sss::scene::testing
