// GltfJson: checks made on the raw JSON before tinygltf reads it. tinygltf 2.7.0 opens
// and decodes URIs while it parses, forms image pointers from buffer views it has not
// range-checked, converts extras recursively and narrows large integers, so these
// checks cannot wait until it returns. Internal to the loader.
#pragma once

#include "scene/LoadError.h"
#include "scene/KhrMaterials.h"
#include "scene/Material.h"

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
    "KHR_lights_punctual", "KHR_mesh_quantization", "KHR_texture_transform",
    "EXT_meshopt_compression", "KHR_draco_mesh_compression"};
bool is_supported_required_extension(const std::string& name);

// o.extensions[name] when `o` has it (check_gltf_schema makes every extensions member an
// object of objects), else nullptr.
const nlohmann::json* find_extension(const nlohmann::json& o, const char* name);

// glTF itself nests about 6 deep; extras may go deeper, but not without bound (a
// recursive parser would overflow the stack).
inline constexpr int kMaxJsonDepth = 64;

// nullopt if no array or object nests deeper than max_depth (strings are skipped).
std::optional<std::string> check_json_depth(std::string_view text, int max_depth);

// EXT_meshopt_compression of one buffer view (the extension's README, "JSON schema
// updates"): [byte_offset, +byte_length) of buffers[buffer] decode into `count`
// elements of `byte_stride` bytes, which fill the view itself.
struct MeshoptView {
  enum class Mode { Attributes, Triangles, Indices };
  enum class Filter { None, Octahedral, Quaternion, Exponential };
  std::size_t buffer = 0;
  std::uint64_t byte_offset = 0, byte_length = 0;
  std::uint64_t byte_stride = 0, count = 0;
  Mode mode = Mode::Attributes;
  Filter filter = Filter::None;
};

// KHR_draco_mesh_compression of one primitive (the extension's README): the Draco
// bitstream in bufferViews[buffer_view], and the Draco attribute id of each semantic.
struct DracoPrimitive {
  std::size_t buffer_view = 0;
  std::vector<std::pair<std::string, std::uint32_t>> attributes;  // {"POSITION", 0}
  // The primitive's indices accessor (it has no bufferView: the indices are Draco's).
  std::optional<std::size_t> indices;
};

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
  // bufferViews[i]'s EXT_meshopt_compression, when the file uses the extension.
  std::vector<std::optional<MeshoptView>> meshopt_views;
  // buffers[i] is a meshopt placeholder: no uri, no data of its own, filled only by
  // decoding its compressed views (a GLB's buffers[0] without uri is the BIN chunk).
  std::vector<bool> placeholder_buffers;
  // meshes[m].primitives[p]'s KHR_draco_mesh_compression, when the file uses it.
  std::vector<std::vector<std::optional<DracoPrimitive>>> draco;
  // The JSON to give tinygltf when it differs from the file's. tinygltf 2.7.0 needs a
  // uri for every buffer but a GLB's BIN chunk, so each placeholder buffer becomes a
  // 1-byte data URI (its data is made after parsing: decode_meshopt, GltfContext.h); and
  // it needs a bufferView in every indices accessor, so a Draco primitive's indices are
  // left out (DracoPrimitive::indices keeps them).
  std::optional<std::string> parser_json;
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
// materials[i].extensions (parse_khr_medium); EXT_meshopt_compression's placeholder
// buffers and compressed views, and KHR_draco_mesh_compression's primitives (the rules
// of their READMEs). The error names the file, the object and the field.
std::variant<GltfJsonFacts, LoadError> check_gltf_json(
    std::string_view text, const std::string& file,
    std::optional<std::uint64_t> glb_bin_bytes = std::nullopt);

}  // namespace sss::scene
