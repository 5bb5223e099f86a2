// GltfJson: checks made on the raw JSON before tinygltf reads it. tinygltf 2.7.0 opens
// and decodes URIs while it parses, forms image pointers from buffer views it has not
// range-checked, converts extras recursively and narrows large integers, so these
// checks cannot wait until it returns. Internal to the loader.
#pragma once

#include "renderer/scene/LoadError.h"
#include "renderer/scene/KhrMaterials.h"
#include "renderer/scene/Material.h"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace sss::scene {

// The extensions a file may require: those the loader implements.
inline constexpr const char* kSupportedRequiredExtensions[] = {
    "KHR_lights_punctual", "KHR_mesh_quantization", "KHR_texture_transform"};
bool is_supported_required_extension(const std::string& name);

// glTF itself nests about 6 deep; extras may go deeper, but not without bound (a
// recursive parser would overflow the stack).
inline constexpr int kMaxJsonDepth = 64;

// nullopt if no array or object nests deeper than max_depth (strings are skipped).
std::optional<std::string> check_json_depth(std::string_view text, int max_depth);

struct GltfJsonFacts {
  std::size_t material_count = 0;
  std::vector<std::optional<SssMaterial>> material_sss;  // materials[i].extras.sss
  // materials[i].extensions' medium extensions (KhrMaterials.h), when it has any.
  std::vector<std::optional<KhrMedium>> material_khr;
  // images[i]'s declared media type ("image/png", "image/jpeg"): its data URI's type or
  // its mimeType; empty when it declares none (a file URI without mimeType).
  std::vector<std::string> image_media_type;
  // Every file URI (not data:), as {object, uri}: {"buffers[0]", "mesh.bin"}.
  std::vector<std::pair<std::string, std::string>> file_uris;
};

// The type of every glTF 2.0 property tinygltf reads and every index into another array
// (GltfSchema.cpp says why this cannot wait for tinygltf). nullopt when all are right.
std::optional<LoadError> check_gltf_schema(const nlohmann::json& root, const std::string& file);

// Checks: the root is an object; check_gltf_schema; extensionsRequired (only
// KHR_lights_punctual); buffers[i].uri and images[i].uri (check_uri, with the buffer's
// byteLength); a buffer without uri only as a GLB's buffers[0], no longer than the BIN
// chunk (`glb_bin_bytes`: the BIN chunk's size for a GLB, nullopt for a .gltf); every
// bufferViews[i] (byte range with 64-bit arithmetic, stride); images[i].bufferView;
// materials[i].extras.sss (parse_sss_extras) and the medium extensions in
// materials[i].extensions (parse_khr_medium). The error names the file, the object and
// the field.
std::variant<GltfJsonFacts, LoadError> check_gltf_json(
    std::string_view text, const std::string& file,
    std::optional<std::uint64_t> glb_bin_bytes = std::nullopt);

}  // namespace sss::scene
