#include "renderer/scene/GltfJson.h"

#include "renderer/scene/GltfUri.h"
#include "renderer/scene/SssExtras.h"

#include <nlohmann/json.hpp>

namespace sss::scene {

bool is_supported_required_extension(const std::string& name) {
  for (const char* e : kSupportedRequiredExtensions)
    if (name == e) return true;
  return false;
}

namespace {

using nlohmann::json;

std::string at(const char* array, std::size_t i) {
  return std::string(array) + "[" + std::to_string(i) + "]";
}

std::optional<std::uint64_t> as_uint(const json& v) {
  if (v.is_number_unsigned()) return v.get<std::uint64_t>();
  if (v.is_number_integer() && v.get<std::int64_t>() >= 0) return v.get<std::uint64_t>();
  return std::nullopt;
}

struct Checker {
  const std::string& file;
  const json& root;

  LoadError fail(std::string object, std::string field, std::string message) const {
    return LoadError{file, std::move(object), std::move(field), std::move(message)};
  }

  // The array root[name], or an empty one if absent.
  std::variant<const json*, LoadError> array(const char* name) const {
    static const json kEmpty = json::array();
    if (!root.contains(name)) return &kEmpty;
    const json& a = root.at(name);
    if (!a.is_array()) return fail(name, "", "must be an array");
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!a[i].is_object()) return fail(at(name, i), "", "must be a JSON object");
    return &a;
  }

  // An unsigned integer member; `required` or defaulting to `fallback`.
  std::variant<std::uint64_t, LoadError> uint_member(const json& o, const std::string& object,
                                                     const char* key, bool required,
                                                     std::uint64_t fallback = 0) const {
    if (!o.contains(key)) {
      if (required) return fail(object, key, "is required");
      return fallback;
    }
    const auto v = as_uint(o.at(key));
    if (!v) return fail(object, key, "must be a non-negative integer, got " + o.at(key).dump());
    return *v;
  }
};

}  // namespace

// `auto var = expr` for a variant<T, LoadError>, returning the error.
#define SSS_TRY(var, expr)                                                \
  auto var##_r = (expr);                                                  \
  if (auto* var##_e = std::get_if<LoadError>(&var##_r)) return std::move(*var##_e); \
  auto var = std::get<0>(var##_r)

std::optional<std::string> check_json_depth(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == '[' || c == '{') {
      if (++depth > max_depth)
        return "JSON nests deeper than " + std::to_string(max_depth) + " levels";
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::nullopt;
}

std::variant<GltfJsonFacts, LoadError> check_gltf_json(std::string_view text,
                                                       const std::string& file,
                                                       std::optional<std::uint64_t> glb_bin_bytes) {
  if (auto e = check_json_depth(text, kMaxJsonDepth)) return LoadError{file, "", "", *e};
  const json root = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded()) return LoadError{file, "", "", "is not valid JSON"};
  if (!root.is_object()) return LoadError{file, "", "", "the JSON root must be an object"};
  if (auto e = check_gltf_schema(root, file)) return *e;
  const Checker c{file, root};

  std::vector<std::pair<std::string, std::string>> file_uris;
  SSS_TRY(buffers, c.array("buffers"));
  std::vector<std::uint64_t> buffer_bytes;
  for (std::size_t i = 0; i < buffers->size(); ++i) {
    const json& b = (*buffers)[i];
    SSS_TRY(length, c.uint_member(b, at("buffers", i), "byteLength", true));
    if (length == 0) return c.fail(at("buffers", i), "byteLength", "must be >= 1");
    buffer_bytes.push_back(length);
    if (!b.contains("uri")) {  // the GLB's BIN chunk (glTF 2.0 §4.4.3.3)
      if (!glb_bin_bytes || i != 0)
        return c.fail(at("buffers", i), "uri",
                      glb_bin_bytes ? "is required; only buffers[0] of a GLB may omit it (the BIN chunk)"
                                    : "is required in a .gltf file (only a GLB's buffers[0] may omit it)");
      if (length > *glb_bin_bytes)
        return c.fail(at("buffers", i), "byteLength",
                      std::to_string(length) + " bytes, but the GLB's BIN chunk has " +
                          std::to_string(*glb_bin_bytes) + (*glb_bin_bytes ? "" : " (it has none)"));
      continue;
    }
    if (!b["uri"].is_string()) return c.fail(at("buffers", i), "uri", "must be a string");
    if (auto e = check_uri(b["uri"].get<std::string>(), UriUse::Buffer, length))
      return c.fail(at("buffers", i), "uri", *e);
    if (b["uri"].get<std::string>().rfind("data:", 0) != 0)
      file_uris.emplace_back(at("buffers", i), b["uri"].get<std::string>());
  }

  // Every buffer view lies inside its buffer (tinygltf forms image pointers from them).
  SSS_TRY(views, c.array("bufferViews"));
  for (std::size_t v = 0; v < views->size(); ++v) {
    const json& view = (*views)[v];
    const std::string name = at("bufferViews", v);
    SSS_TRY(b, c.uint_member(view, name, "buffer", true));
    SSS_TRY(offset, c.uint_member(view, name, "byteOffset", false, 0));
    SSS_TRY(length, c.uint_member(view, name, "byteLength", true));
    SSS_TRY(stride, c.uint_member(view, name, "byteStride", false, 0));
    if (b >= buffer_bytes.size())
      return c.fail(name, "buffer", "buffers[" + std::to_string(b) +
                                        "] does not exist (the file has " +
                                        std::to_string(buffer_bytes.size()) + ")");
    std::uint64_t end = 0;
    if (length == 0) return c.fail(name, "byteLength", "must be >= 1");
    if (__builtin_add_overflow(offset, length, &end) || end > buffer_bytes[b])
      return c.fail(name, "byteLength",
                    "bytes [" + std::to_string(offset) + ", +" + std::to_string(length) +
                        ") run past the " + std::to_string(buffer_bytes[b]) +
                        " bytes of buffers[" + std::to_string(b) + "]");
    if (view.contains("byteStride") && (stride < 4 || stride > 252 || stride % 4 != 0))
      return c.fail(name, "byteStride", "must be a multiple of 4 in [4, 252], got " +
                                            std::to_string(stride));
  }

  SSS_TRY(images, c.array("images"));
  std::vector<std::string> media_types(images->size());
  for (std::size_t i = 0; i < images->size(); ++i) {
    const json& img = (*images)[i];
    const std::string object = at("images", i);
    if (img.contains("uri") == img.contains("bufferView"))
      return c.fail(object, "", "needs exactly one of uri and bufferView");
    if (img.contains("mimeType")) media_types[i] = img["mimeType"].get<std::string>();  // schema: png/jpeg
    if (img.contains("uri")) {
      if (!img["uri"].is_string()) return c.fail(object, "uri", "must be a string");
      const std::string uri = img["uri"].get<std::string>();
      if (auto e = check_uri(uri, UriUse::Image)) return c.fail(object, "uri", *e);
      if (uri.rfind("data:", 0) == 0) {
        const std::string type = uri.substr(5, uri.find(';') - 5);  // check_uri: png or jpeg
        if (!media_types[i].empty() && media_types[i] != type)
          return c.fail(object, "mimeType", "is \"" + media_types[i] + "\" but the data URI is " + type);
        media_types[i] = type;
      } else {
        file_uris.emplace_back(object, uri);
      }
      continue;
    }
    SSS_TRY(v, c.uint_member(img, object, "bufferView", true));
    if (v >= views->size())
      return c.fail(object, "bufferView", "bufferViews[" + std::to_string(v) +
                                              "] does not exist (the file has " +
                                              std::to_string(views->size()) + ")");
  }

  // Required extensions: those the loader implements (GltfContext.h).
  if (root.contains("extensionsRequired")) {
    const json& req = root["extensionsRequired"];
    if (!req.is_array()) return c.fail("extensionsRequired", "", "must be an array");
    for (std::size_t i = 0; i < req.size(); ++i)
      if (!req[i].is_string() || !is_supported_required_extension(req[i].get<std::string>()))
        return c.fail("extensionsRequired", "[" + std::to_string(i) + "]",
                      req[i].dump() + " is required by the file but not supported");
  }

  SSS_TRY(materials, c.array("materials"));
  GltfJsonFacts facts;
  facts.image_media_type = std::move(media_types);
  facts.file_uris = std::move(file_uris);
  facts.material_count = materials->size();
  facts.material_sss.resize(materials->size());
  facts.material_khr.resize(materials->size());
  for (std::size_t i = 0; i < materials->size(); ++i) {
    const json& m = (*materials)[i];
    if (m.contains("extensions")) {
      auto khr = parse_khr_medium(m["extensions"]);
      if (auto* e = std::get_if<FieldError>(&khr))
        return c.fail(at("materials", i), "extensions." + e->field, e->message);
      if (std::get<KhrMedium>(khr).any()) facts.material_khr[i] = std::get<KhrMedium>(std::move(khr));
    }
    if (!m.contains("extras") || !m["extras"].is_object() || !m["extras"].contains("sss"))
      continue;
    auto sss = parse_sss_extras(m["extras"]["sss"]);
    if (auto* e = std::get_if<FieldError>(&sss))
      return c.fail(at("materials", i), "extras.sss" + (e->field.empty() ? "" : "." + e->field),
                    e->message);
    facts.material_sss[i] = std::get<SssMaterial>(std::move(sss));
  }
  return facts;
}

#undef SSS_TRY

}  // namespace sss::scene
