#include "scene/GltfJson.h"

#include "scene/GltfUri.h"
#include "scene/SssExtras.h"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace sss::scene {

bool is_supported_required_extension(const std::string& name) {
  for (const char* e : kSupportedRequiredExtensions)
    if (name == e) return true;
  return false;
}

const nlohmann::json* find_extension(const nlohmann::json& o, const char* name) {
  if (!o.is_object() || !o.contains("extensions") || !o["extensions"].is_object() ||
      !o["extensions"].contains(name))
    return nullptr;
  return &o["extensions"][name];
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

bool uses_extension(const json& root, const char* name) {
  if (!root.contains("extensionsUsed")) return false;  // the schema checked its type
  for (const json& e : root["extensionsUsed"])
    if (e == name) return true;
  return false;
}

// The rules that tie EXT_meshopt_compression's fields to each other and to the parent
// view (its README, "JSON schema updates" and "Fallback buffers"; the schema checked
// each field's type). `view_length` and `view_stride` (0: not given) are the parent's.
std::variant<MeshoptView, LoadError> check_meshopt_view(const Checker& c, const json& e,
                                                        const std::string& view, std::uint64_t view_length,
                                                        std::uint64_t view_stride,
                                                        const std::vector<std::uint64_t>& buffer_bytes,
                                                        const std::vector<bool>& fallback) {
  const std::string name = view + ".extensions.EXT_meshopt_compression";
  MeshoptView m;
  m.buffer = e["buffer"].get<std::size_t>();
  m.byte_offset = e.value("byteOffset", std::uint64_t{0});
  m.byte_length = e["byteLength"].get<std::uint64_t>();
  m.byte_stride = e["byteStride"].get<std::uint64_t>();
  m.count = e["count"].get<std::uint64_t>();
  const std::string mode = e["mode"].get<std::string>();
  const std::string filter = e.value("filter", std::string("NONE"));
  m.mode = mode == "ATTRIBUTES" ? MeshoptView::Mode::Attributes
           : mode == "TRIANGLES" ? MeshoptView::Mode::Triangles
                                 : MeshoptView::Mode::Indices;
  m.filter = filter == "OCTAHEDRAL"    ? MeshoptView::Filter::Octahedral
             : filter == "QUATERNION"  ? MeshoptView::Filter::Quaternion
             : filter == "EXPONENTIAL" ? MeshoptView::Filter::Exponential
                                       : MeshoptView::Filter::None;
  const std::string buffer = "buffers[" + std::to_string(m.buffer) + "]";
  if (fallback[m.buffer])
    return c.fail(name, "buffer", buffer + " is a fallback buffer; compressed bytes must come from another");
  std::uint64_t end = 0;
  if (__builtin_add_overflow(m.byte_offset, m.byte_length, &end) || end > buffer_bytes[m.buffer])
    return c.fail(name, "byteLength", "bytes [" + std::to_string(m.byte_offset) + ", +" +
                                          std::to_string(m.byte_length) + ") run past the " +
                                          std::to_string(buffer_bytes[m.buffer]) + " bytes of " + buffer);
  if (view_stride && view_stride != m.byte_stride)
    return c.fail(name, "byteStride", std::to_string(m.byte_stride) + " differs from the view's byteStride " +
                                          std::to_string(view_stride));
  std::uint64_t decoded = 0;
  if (__builtin_mul_overflow(m.byte_stride, m.count, &decoded) || decoded != view_length)
    return c.fail(name, "count", std::to_string(m.count) + " elements of " + std::to_string(m.byte_stride) +
                                     " bytes do not fill the view's byteLength " + std::to_string(view_length));
  const bool indices = m.mode != MeshoptView::Mode::Attributes;
  if (!indices && m.byte_stride % 4 != 0)
    return c.fail(name, "byteStride", "must be a multiple of 4 (at most 256) in mode ATTRIBUTES, got " +
                                          std::to_string(m.byte_stride));
  if (indices && m.byte_stride != 2 && m.byte_stride != 4)
    return c.fail(name, "byteStride", "must be 2 or 4 in mode " + mode + ", got " + std::to_string(m.byte_stride));
  if (m.mode == MeshoptView::Mode::Triangles && m.count % 3 != 0)
    return c.fail(name, "count", std::to_string(m.count) + " is not a multiple of 3 (mode TRIANGLES)");
  if (indices && m.filter != MeshoptView::Filter::None)
    return c.fail(name, "filter", "must be NONE in mode " + mode + ", got " + filter);
  const std::uint64_t s = m.byte_stride;
  if ((m.filter == MeshoptView::Filter::Octahedral && s != 4 && s != 8) ||
      (m.filter == MeshoptView::Filter::Quaternion && s != 8))
    return c.fail(name, "byteStride", std::to_string(s) + " does not suit filter " + filter +
                                          (m.filter == MeshoptView::Filter::Quaternion ? " (it needs 8)"
                                                                                       : " (it needs 4 or 8)"));
  return m;
}

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
    // The parser (nlohmann) reads a NUL as the end of its input: nothing after one is
    // parsed, so nothing after one nests (the fuzzer's text with garbage past a NUL).
    if (c == '\0') break;
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

namespace {

// The buffers as check_gltf_json learns them: their sizes, which ones are
// EXT_meshopt_compression fallbacks (flagged, or placeholders without a uri).
struct BufferFacts {
  std::vector<std::uint64_t> bytes;
  std::vector<bool> fallback, placeholder;
};

// buffers[]: each one's length, its uri (or the GLB's BIN chunk, or a meshopt placeholder);
// the files they name go to file_uris.
std::optional<LoadError> check_buffers(const Checker& c, bool meshopt,
                                       std::optional<std::uint64_t> glb_bin_bytes, BufferFacts& out,
                                       std::vector<std::pair<std::string, std::string>>& file_uris) {
  SSS_TRY(buffers, c.array("buffers"));
  std::vector<std::uint64_t>& buffer_bytes = out.bytes;
  std::vector<bool>& fallback = out.fallback;
  std::vector<bool>& placeholder = out.placeholder;
  fallback.assign(buffers->size(), false);
  placeholder.assign(buffers->size(), false);
  for (std::size_t i = 0; i < buffers->size(); ++i) {
    const json& b = (*buffers)[i];
    SSS_TRY(length, c.uint_member(b, at("buffers", i), "byteLength", true));
    if (length == 0) return c.fail(at("buffers", i), "byteLength", "must be >= 1");
    buffer_bytes.push_back(length);
    if (const json* e = find_extension(b, "EXT_meshopt_compression"))
      fallback[i] = meshopt && e->value("fallback", false);  // schema: a boolean
    const bool bin_chunk = glb_bin_bytes && i == 0;  // glTF 2.0 §4.4.3.3
    if (!b.contains("uri") && !bin_chunk && meshopt) {
      // The extension's README, "Fallback buffers": its views are all compressed.
      fallback[i] = placeholder[i] = true;
      continue;
    }
    if (!b.contains("uri")) {  // the GLB's BIN chunk
      if (!bin_chunk)
        return c.fail(at("buffers", i), "uri",
                      glb_bin_bytes ? "is required; only buffers[0] of a GLB may omit it (the BIN chunk), "
                                      "or a placeholder of EXT_meshopt_compression"
                                    : "is required in a .gltf file (only a GLB's buffers[0] may omit it, "
                                      "or a placeholder of EXT_meshopt_compression)");
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

  return std::nullopt;
}

// bufferViews[]: every view lies inside its buffer (tinygltf forms image pointers from
// them); the EXT_meshopt_compression ones are decoded later (meshopt_views).
std::optional<LoadError> check_views(const Checker& c, bool meshopt, const BufferFacts& buffers,
                                     std::vector<std::optional<MeshoptView>>& meshopt_views) {
  SSS_TRY(views, c.array("bufferViews"));
  const std::vector<std::uint64_t>& buffer_bytes = buffers.bytes;
  const std::vector<bool>& fallback = buffers.fallback;
  const std::vector<bool>& placeholder = buffers.placeholder;
  meshopt_views.assign(views->size(), std::nullopt);
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
    const json* mx = find_extension(view, "EXT_meshopt_compression");
    if (mx && !meshopt)
      return c.fail(name, "extensions.EXT_meshopt_compression",
                    "is used but \"EXT_meshopt_compression\" is not in extensionsUsed");
    if (!mx && fallback[b])
      return c.fail(name, "buffer",
                    "buffers[" + std::to_string(b) + "] is an EXT_meshopt_compression fallback " +
                        (placeholder[b] ? "placeholder without data" : "buffer") +
                        "; only compressed views may refer to it");
    if (mx) {
      auto m = check_meshopt_view(c, *mx, name, length, view.contains("byteStride") ? stride : 0,
                                  buffer_bytes, fallback);
      if (auto* e = std::get_if<LoadError>(&m)) return std::move(*e);
      meshopt_views[v] = std::get<MeshoptView>(m);
    }
  }

  return std::nullopt;
}

// images[]: one of uri and bufferView, each image's media type; the files they name go to
// file_uris.
std::optional<LoadError> check_images(const Checker& c,
                                      const std::vector<std::optional<MeshoptView>>& meshopt_views,
                                      std::vector<std::string>& media_types,
                                      std::vector<std::pair<std::string, std::string>>& file_uris) {
  SSS_TRY(images, c.array("images"));
  const std::size_t view_count = meshopt_views.size();
  media_types.assign(images->size(), std::string());
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
    if (v >= view_count)
      return c.fail(object, "bufferView", "bufferViews[" + std::to_string(v) +
                                              "] does not exist (the file has " +
                                              std::to_string(view_count) + ")");
    // tinygltf reads an image's view before meshopt data is decoded (compressors leave
    // images uncompressed: their formats are compressed already).
    if (meshopt_views[v])
      return c.fail(object, "bufferView", "bufferViews[" + std::to_string(v) +
                                              "] is EXT_meshopt_compression-compressed; images "
                                              "in compressed views are not supported");
  }

  return std::nullopt;
}

// Required extensions: those the loader implements (GltfContext.h).
std::optional<LoadError> check_required_extensions(const Checker& c) {
  const json& root = c.root;
  if (root.contains("extensionsRequired")) {
    const json& req = root["extensionsRequired"];
    if (!req.is_array()) return c.fail("extensionsRequired", "", "must be an array");
    for (std::size_t i = 0; i < req.size(); ++i)
      if (!req[i].is_string() || !is_supported_required_extension(req[i].get<std::string>()))
        return c.fail("extensionsRequired", "[" + std::to_string(i) + "]",
                      req[i].dump() + " is required by the file but not supported");
  }
  return std::nullopt;
}

// KHR_draco_mesh_compression's primitives (the schema checked the types and the view index).
std::optional<LoadError> read_draco(const Checker& c, bool draco, GltfJsonFacts& facts) {
  const json& root = c.root;
  if (root.contains("meshes")) {
    const json& meshes = root["meshes"];
    facts.draco.resize(meshes.size());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const json& prims = meshes[m]["primitives"];
      facts.draco[m].resize(prims.size());
      for (std::size_t p = 0; p < prims.size(); ++p) {
        const json* e = find_extension(prims[p], "KHR_draco_mesh_compression");
        if (!e) continue;
        const std::string name = at("meshes", m) + "." + at("primitives", p);
        if (!draco)
          return c.fail(name, "extensions.KHR_draco_mesh_compression",
                        "is used but \"KHR_draco_mesh_compression\" is not in extensionsUsed");
        DracoPrimitive d;
        d.buffer_view = (*e)["bufferView"].get<std::size_t>();
        for (const auto& item : (*e)["attributes"].items())
          d.attributes.emplace_back(item.key(), item.value().get<std::uint32_t>());
        if (prims[p].contains("indices")) d.indices = prims[p]["indices"].get<std::size_t>();
        facts.draco[m][p] = std::move(d);
      }
    }
  }  return std::nullopt;
}

// What tinygltf 2.7.0 cannot parse as the file has it (GltfJsonFacts::parser_json): a
// placeholder buffer gets one byte of data, a Draco primitive loses its indices. None when
// the file parses as it is.
std::optional<std::string> parser_text(const json& root, const GltfJsonFacts& facts) {
  const std::vector<bool>& placeholder = facts.placeholder_buffers;
  std::optional<json> parser_root;
  for (std::size_t i = 0; i < placeholder.size(); ++i)
    if (placeholder[i]) {
      if (!parser_root) parser_root = root;
      (*parser_root)["buffers"][i]["uri"] = "data:application/octet-stream;base64,AA==";
      (*parser_root)["buffers"][i]["byteLength"] = 1;
    }
  for (std::size_t m = 0; m < facts.draco.size(); ++m)
    for (std::size_t p = 0; p < facts.draco[m].size(); ++p)
      if (facts.draco[m][p] && facts.draco[m][p]->indices) {
        if (!parser_root) parser_root = root;
        (*parser_root)["meshes"][m]["primitives"][p].erase("indices");
      }
  if (!parser_root) return std::nullopt;
  return parser_root->dump();
}

// materials[]: each one's KHR volume / subsurface extensions and extras.sss.
std::optional<LoadError> read_materials(const Checker& c, const json& materials, GltfJsonFacts& facts) {
  facts.material_count = materials.size();
  facts.material_sss.resize(materials.size());
  facts.material_khr.resize(materials.size());
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const json& m = materials[i];
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
  return std::nullopt;
}

}  // namespace

std::variant<GltfJsonFacts, LoadError> check_gltf_json(std::string_view text,
                                                       const std::string& file,
                                                       std::optional<std::uint64_t> glb_bin_bytes) {
  if (auto e = check_json_depth(text, kMaxJsonDepth)) return LoadError{file, "", "", *e};
  const json root = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded()) return LoadError{file, "", "", "is not valid JSON"};
  if (!root.is_object()) return LoadError{file, "", "", "the JSON root must be an object"};
  if (auto e = check_gltf_schema(root, file)) return *e;
  const Checker c{file, root};

  const bool meshopt = uses_extension(root, "EXT_meshopt_compression");
  const bool draco = uses_extension(root, "KHR_draco_mesh_compression");
  std::vector<std::pair<std::string, std::string>> file_uris;
  BufferFacts buffers;
  if (auto e = check_buffers(c, meshopt, glb_bin_bytes, buffers, file_uris)) return std::move(*e);
  std::vector<std::optional<MeshoptView>> meshopt_views;
  if (auto e = check_views(c, meshopt, buffers, meshopt_views)) return std::move(*e);
  std::vector<std::string> media_types;
  if (auto e = check_images(c, meshopt_views, media_types, file_uris)) return std::move(*e);
  if (auto e = check_required_extensions(c)) return std::move(*e);

  SSS_TRY(materials, c.array("materials"));
  GltfJsonFacts facts;
  facts.image_media_type = std::move(media_types);
  facts.file_uris = std::move(file_uris);
  facts.meshopt_views = std::move(meshopt_views);
  facts.placeholder_buffers = buffers.placeholder;
  if (auto e = read_draco(c, draco, facts)) return std::move(*e);
  facts.parser_json = parser_text(root, facts);
  if (auto e = read_materials(c, *materials, facts)) return std::move(*e);
  return facts;
}

#undef SSS_TRY

}  // namespace sss::scene
