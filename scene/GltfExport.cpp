#include "scene/GltfExport.h"

#include "scene/GltfFile.h"
#include "scene/GltfJson.h"
#include "scene/GltfLoader.h"
#include "scene/KhrMaterials.h"
#include "scene/SssExtras.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>
#include <set>
#include <system_error>

namespace sss::scene {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using ordered_json = nlohmann::ordered_json;

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(b, ec) && fs::equivalent(a, b, ec)) return true;
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

// Does any buffer or image name an external file (a URI that is not a data URI)?
bool has_relative_uris(const ordered_json& doc) {
  for (const char* list : {"buffers", "images"}) {
    if (!doc.contains(list) || !doc[list].is_array()) continue;
    for (const ordered_json& item : doc[list])
      if (item.is_object() && item.contains("uri") && item["uri"].is_string() &&
          item["uri"].get<std::string>().rfind("data:", 0) != 0)
        return true;
  }
  return false;
}

// Writes extras.sss (and the KHR extensions beside it) into doc's materials and lists
// the extensions as used; an error names the material and the field that refused it.
std::optional<LoadError> write_sss_materials(ordered_json& doc, const std::vector<Material>& materials,
                                             double mm_per_unit, const std::string& input) {
  const auto fail = [&](std::string object, std::string field, std::string message) {
    return LoadError{input, std::move(object), std::move(field), std::move(message)};
  };
  if (!doc.contains("materials") || !doc["materials"].is_array())
    return fail("materials", "", "the file has no materials to write SSS into");
  ordered_json& list = doc["materials"];
  const std::size_t count = std::min(list.size(), materials.size());
  std::set<std::string> used;  // the KHR extensions written
  for (std::size_t i = 0; i < count; ++i) {
    ordered_json& m = list[i];
    if (!m.is_object())
      return fail("materials[" + std::to_string(i) + "]", "", "is not a JSON object");
    const bool had = m.contains("extras") && m["extras"].is_object() && m["extras"].contains("sss");
    if (!materials[i].sss.enabled && !had) continue;
    if (!m.contains("extras")) m["extras"] = ordered_json::object();
    if (!m["extras"].is_object())
      return fail("materials[" + std::to_string(i) + "]", "extras",
                  "is not a JSON object, so extras.sss cannot be added");
    m["extras"]["sss"] = ordered_json::parse(sss_extras_json(materials[i].sss).dump());
    if (!materials[i].sss.enabled) continue;
    // The standard extensions beside it, for other tools (extras.sss still wins here).
    const json khr = khr_extensions_json(materials[i].sss, mm_per_unit);
    if (khr.empty()) continue;
    if (!m.contains("extensions")) m["extensions"] = ordered_json::object();
    if (!m["extensions"].is_object())
      return fail("materials[" + std::to_string(i) + "]", "extensions",
                  "is not a JSON object, so the KHR material extensions cannot be added");
    for (const auto& [name, value] : khr.items()) {
      m["extensions"][name] = ordered_json::parse(value.dump());
      used.insert(name);
    }
  }
  // Listed as used, never as required: drafts among them, and extras.sss holds it all.
  if (!used.empty()) {
    if (!doc.contains("extensionsUsed") || !doc["extensionsUsed"].is_array())
      doc["extensionsUsed"] = ordered_json::array();
    for (const std::string& name : used)
      if (std::find(doc["extensionsUsed"].begin(), doc["extensionsUsed"].end(), name) ==
          doc["extensionsUsed"].end())
        doc["extensionsUsed"].push_back(name);
  }

  return std::nullopt;
}

}  // namespace

std::variant<std::string, LoadError> gltf_with_sss_materials(const std::string& input,
                                                             const std::vector<Material>& materials,
                                                             const std::string& output,
                                                             double mm_per_unit) {
  const auto fail = [&](std::string object, std::string field, std::string message) {
    return LoadError{input, std::move(object), std::move(field), std::move(message)};
  };
  if (output.empty()) return fail("", "", "no output file name given");
  if (same_file(input, output))
    return fail("", "", "will not overwrite the input file; choose another name");
  auto read = read_file_capped(input, LoadOptions{}.max_file_bytes);
  if (auto* msg = std::get_if<std::string>(&read)) return fail("", "", *msg);
  const std::vector<unsigned char>& bytes = std::get<std::vector<unsigned char>>(read);

  const bool glb = has_glb_magic(bytes);
  std::string_view json_text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  std::span<const unsigned char> bin;
  if (glb) {
    auto layout = parse_glb(bytes);
    if (auto* e = std::get_if<FieldError>(&layout)) return fail("glb", e->field, e->message);
    json_text = std::get<GlbLayout>(layout).json;
    bin = std::get<GlbLayout>(layout).bin;
  }
  if (auto e = check_json_depth(json_text, kMaxJsonDepth)) return fail("", "", *e);
  ordered_json doc = ordered_json::parse(json_text.begin(), json_text.end(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return fail("", "", "is not a glTF JSON object");

  if (has_relative_uris(doc)) {
    std::error_code ec;
    const fs::path in_dir = fs::weakly_canonical(fs::absolute(input).parent_path(), ec);
    const fs::path out_dir = fs::weakly_canonical(fs::absolute(output).parent_path(), ec);
    if (in_dir != out_dir)
      return fail("", "", "refers to external files by relative URI, so its copy must be saved "
                          "in the same folder (" + in_dir.string() + ")");
  }

  if (auto e = write_sss_materials(doc, materials, mm_per_unit, input)) return *e;

  std::string text = doc.dump(2);
  if (!glb) return text + "\n";
  const std::vector<unsigned char> out = rebuild_glb(GlbLayout{text, bin});
  return std::string(reinterpret_cast<const char*>(out.data()), out.size());
}

std::string unused_path(const std::string& wanted) {
  std::error_code ec;
  if (!fs::exists(wanted, ec)) return wanted;
  const fs::path p(wanted);
  for (int n = 2;; ++n) {
    fs::path candidate = p.parent_path() / (p.stem().string() + "-" + std::to_string(n) +
                                            p.extension().string());
    if (!fs::exists(candidate, ec)) return candidate.string();
  }
}

std::string default_export_path(const std::string& input) {
  const fs::path p(input);
  return unused_path((p.parent_path() / (p.stem().string() + "-sss" + p.extension().string())).string());
}

}  // namespace sss::scene
