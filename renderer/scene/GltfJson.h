// GltfJson: checks made on the raw JSON before tinygltf reads it. tinygltf 2.7.0 opens
// and decodes URIs while it parses, forms image pointers from buffer views it has not
// range-checked, converts extras recursively and narrows large integers, so these
// checks cannot wait until it returns. Internal to the loader.
#pragma once

#include "renderer/scene/LoadError.h"
#include "renderer/scene/Material.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace sss::scene {

// glTF itself nests about 6 deep; extras may go deeper, but not without bound (a
// recursive parser would overflow the stack).
inline constexpr int kMaxJsonDepth = 64;

// nullopt if no array or object nests deeper than max_depth (strings are skipped).
std::optional<std::string> check_json_depth(std::string_view text, int max_depth);

struct GltfJsonFacts {
  std::size_t material_count = 0;
  std::vector<std::optional<SssMaterial>> material_sss;  // materials[i].extras.sss
};

// Checks: the root is an object; extensionsRequired (only KHR_lights_punctual);
// buffers[i].uri and images[i].uri (check_uri, with the buffer's byteLength); every
// bufferViews[i] (buffer index, byte range with 64-bit arithmetic, stride);
// images[i].bufferView; materials[i].extras.sss (parse_sss_extras). The error names the
// file, the object and the field.
std::variant<GltfJsonFacts, LoadError> check_gltf_json(std::string_view text,
                                                       const std::string& file);

}  // namespace sss::scene
