#include "scene/GltfUri.h"

#include "scene/GltfFile.h"

#include <array>

namespace sss::scene {

namespace {

bool is_base64_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
         c == '+' || c == '/';
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::optional<std::string> percent_decode(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '%') {
      out += s[i];
      continue;
    }
    if (i + 2 >= s.size()) return std::nullopt;
    const int hi = hex_value(s[i + 1]), lo = hex_value(s[i + 2]);
    if (hi < 0 || lo < 0) return std::nullopt;
    out += static_cast<char>(hi * 16 + lo);
    i += 2;
  }
  return out;
}

// The path rules, applied to the URI as written and as decoded.
std::optional<std::string> check_path(std::string_view p, const char* form) {
  const std::string where = form;
  if (p.empty()) return "is empty" + where;
  for (char c : p)
    if (static_cast<unsigned char>(c) < 0x20) return "contains a control character" + where;
  if (p.find('\\') != std::string_view::npos) return "contains a backslash" + where;
  if (p.front() == '/') return "is an absolute path" + where + "; only relative paths are allowed";
  std::size_t start = 0;
  while (start <= p.size()) {
    const std::size_t end = std::min(p.find('/', start), p.size());
    if (p.substr(start, end - start) == "..")
      return "has a \"..\" segment" + where + "; files must lie in the glTF file's folder";
    start = end + 1;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::uint64_t> base64_decoded_size(std::string_view text) {
  if (text.empty() || text.size() % 4 != 0) return std::nullopt;
  std::size_t pad = 0;
  if (text.back() == '=') pad = text[text.size() - 2] == '=' ? 2 : 1;
  for (std::size_t i = 0; i < text.size() - pad; ++i)
    if (!is_base64_char(text[i])) return std::nullopt;
  return text.size() / 4 * 3 - pad;
}

std::optional<std::string> check_uri(std::string_view uri, UriUse use,
                                     std::optional<std::uint64_t> expected_bytes) {
  if (uri.empty()) return "is empty";
  if (uri.substr(0, 5) == "data:") {
    const std::size_t comma = uri.find(',');
    if (comma == std::string_view::npos) return "is a data URI without a ','";
    const std::string_view header = uri.substr(5, comma - 5);
    constexpr std::string_view kB64 = ";base64";
    if (header.size() < kB64.size() || header.substr(header.size() - kB64.size()) != kB64)
      return "is a data URI that is not base64";
    const std::string_view type = header.substr(0, header.size() - kB64.size());
    const std::array<std::string_view, 2> allowed =
        use == UriUse::Buffer
            ? std::array<std::string_view, 2>{"application/octet-stream", "application/gltf-buffer"}
            : std::array<std::string_view, 2>{"image/png", "image/jpeg"};
    if (type != allowed[0] && type != allowed[1])
      return "is a data URI of type \"" + std::string(type) + "\"; expected " +
             std::string(allowed[0]) + " or " + std::string(allowed[1]);
    const auto size = base64_decoded_size(uri.substr(comma + 1));
    if (!size)
      return "has a payload that is not valid base64 (alphabet A-Z a-z 0-9 + /, length a "
             "multiple of 4, '=' only as final padding)";
    if (expected_bytes && *size != *expected_bytes)
      return "decodes to " + std::to_string(*size) + " bytes but byteLength is " +
             std::to_string(*expected_bytes);
    return std::nullopt;
  }
  const std::size_t colon = uri.find(':'), slash = uri.find('/');
  if (colon != std::string_view::npos && (slash == std::string_view::npos || colon < slash))
    return "has a scheme (\"" + std::string(uri.substr(0, colon + 1)) +
           "\"); only relative file paths and data: URIs are allowed";
  if (auto e = check_path(uri, "")) return e;
  const auto decoded = percent_decode(uri);
  if (!decoded) return "has a malformed percent-escape";
  if (auto e = check_path(*decoded, " once percent-decoded")) return e;
  return std::nullopt;
}

std::string decode_file_uri(std::string_view uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%' && i + 2 < uri.size() && hex_value(uri[i + 1]) >= 0 && hex_value(uri[i + 2]) >= 0) {
      out += static_cast<char>(hex_value(uri[i + 1]) * 16 + hex_value(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

bool FileSandbox::contains(const std::string& path) const {
  const std::filesystem::path p = std::filesystem::path(path).lexically_normal();
  const std::filesystem::path rel = p.lexically_relative(root);
  if (rel.empty() || rel == "." || rel.is_absolute()) return false;
  for (const auto& part : rel)
    if (part == "..") return false;
  return true;
}

bool FileSandbox::resolves_inside(const std::string& path) const {
  if (!contains(path)) return false;
  std::error_code ec;
  const std::filesystem::path real = std::filesystem::canonical(path, ec);
  if (ec) return false;
  const std::filesystem::path real_root = std::filesystem::canonical(root, ec);
  if (ec) return false;
  FileSandbox resolved = *this;
  resolved.root = real_root;
  return resolved.contains(real.string());
}

tinygltf::FsCallbacks sandbox_callbacks(FileSandbox* sandbox) {
  tinygltf::FsCallbacks fs{};
  fs.user_data = sandbox;
  fs.FileExists = [](const std::string& path, void* user) {
    const auto* box = static_cast<const FileSandbox*>(user);
    std::error_code ec;
    return box->resolves_inside(path) && std::filesystem::is_regular_file(path, ec);
  };
  fs.ExpandFilePath = [](const std::string& path, void*) { return path; };  // no ~, no $VAR
  fs.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err,
                        const std::string& path, void* user) {
    auto* box = static_cast<FileSandbox*>(user);
    if (!box->resolves_inside(path)) {
      if (err) *err += path + ": outside the glTF file's folder (or a link out of it)\n";
      return false;
    }
    auto read = read_file_capped(path, std::min(box->max_file_bytes, box->bytes_left));
    if (auto* msg = std::get_if<std::string>(&read)) {
      if (err) *err += path + ": " + *msg + "\n";
      return false;
    }
    *out = std::move(std::get<std::vector<unsigned char>>(read));
    box->bytes_left -= out->size();
    return true;
  };
  fs.WriteWholeFile = [](std::string* err, const std::string&, const std::vector<unsigned char>&,
                         void*) {
    if (err) *err += "the loader never writes files\n";
    return false;
  };
  return fs;
}

}  // namespace sss::scene
