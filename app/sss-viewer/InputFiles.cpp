#include "InputFiles.h"

#include "scene/GltfFile.h"
#include "scene/GltfLoader.h"
#include "scene/GltfUri.h"

#include <nlohmann/json.hpp>

#include <system_error>

namespace sss::app {

namespace {

namespace fs = std::filesystem;

}  // namespace

std::vector<fs::path> scene_input_files(const std::string& source) {
  if (source.rfind("builtin:", 0) == 0) return {};
  std::vector<fs::path> files{fs::path(source)};
  auto read = scene::read_file_capped(source, scene::LoadOptions{}.max_file_bytes);
  if (!std::holds_alternative<std::vector<unsigned char>>(read)) return files;
  const auto& bytes = std::get<std::vector<unsigned char>>(read);
  std::string_view json(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (scene::has_glb_magic(bytes)) {
    auto layout = scene::parse_glb(bytes);
    if (!std::holds_alternative<scene::GlbLayout>(layout)) return files;
    json = std::get<scene::GlbLayout>(layout).json;
  }
  const nlohmann::json doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (!doc.is_object()) return files;
  const fs::path folder = fs::path(source).parent_path();
  for (const char* list : {"buffers", "images"}) {
    if (!doc.contains(list) || !doc[list].is_array()) continue;
    for (const nlohmann::json& item : doc[list])
      if (item.is_object() && item.contains("uri") && item["uri"].is_string()) {
        const std::string uri = item["uri"].get<std::string>();
        if (uri.rfind("data:", 0) != 0) files.push_back(folder / scene::decode_file_uri(uri));  // as the loader opens it
      }
  }
  return files;
}

std::optional<std::string> refuse_input_overwrite(const std::string& output,
                                                  const std::vector<fs::path>& inputs) {
  std::error_code ec;
  if (output.empty() || !fs::exists(output, ec)) return std::nullopt;  // a new file
  for (const fs::path& input : inputs) {
    std::error_code eq;
    if (fs::equivalent(output, input, eq))
      return "will not overwrite " + output + ": it is " +
             (input == inputs.front() ? std::string("the loaded scene file")
                                      : "a file of the loaded scene (" + inputs.front().string() + ")") +
             "; choose another name";
  }
  return std::nullopt;
}

}  // namespace sss::app
