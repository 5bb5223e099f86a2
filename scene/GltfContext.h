// GltfContext: the state of one load_gltf call, shared by the files that convert each
// part of a tinygltf::Model (GltfAccessor, GltfMesh, GltfMaterial, GltfNodes). Each
// conversion returns Status: nullopt, or the first LoadError. Internal to the loader.
#pragma once

#include "scene/GltfJson.h"
#include "scene/GltfLoader.h"

#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <memory>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace sss::scene {

using Status = std::optional<LoadError>;

struct GltfContext {
  std::string file;
  const LoadOptions& options;
  const tinygltf::Model& model;
  Scene& scene;
  // Encoded bytes of URI images, captured by the image hook (index = images[i]).
  const std::vector<std::vector<unsigned char>>& uri_image_bytes;
  // Declared media type of images[i] (GltfJsonFacts::image_media_type).
  const std::vector<std::string>& image_media_type;
  // KHR_draco_mesh_compression of meshes[m].primitives[p] (GltfJsonFacts::draco).
  const std::vector<std::vector<std::optional<DracoPrimitive>>>& draco;
  std::uint64_t bytes_charged = 0;
  std::vector<std::vector<std::uint32_t>> mesh_primitives;  // glTF mesh -> scene meshes
  std::vector<std::optional<std::uint32_t>> texture_map;     // glTF texture -> scene texture
  std::vector<std::shared_ptr<const ImageRgba8>> images;     // decoded, by glTF image
  bool mesh_quantization = false;  // KHR_mesh_quantization is in extensionsUsed
  // KHR_texture_transform of each material's textures as u' = t[0] u + t[1] v + t[2],
  // v' = t[3] u + t[4] v + t[5]: convert_meshes applies it to TEXCOORD_0 of the
  // primitives drawn with the material (one transform per material; GltfMaterial.cpp).
  std::vector<std::optional<std::array<float, 6>>> uv_transforms;

  LoadError fail(std::string object, std::string field, std::string message) const {
    return LoadError{file, std::move(object), std::move(field), std::move(message)};
  }
  // Reserves `bytes` of the scene budget before they are allocated.
  Status charge(std::uint64_t bytes, const std::string& object);
};

inline std::string indexed(const char* array, std::size_t i) {
  return std::string(array) + "[" + std::to_string(i) + "]";
}
// "does not exist (the file has N)" for an index out of range, else nullopt.
std::optional<std::string> out_of_range(const char* array, long long index, std::size_t size);
// A float's text for messages.
std::string number_text(double v);

// Every buffer view: buffer index, byte range inside the buffer, stride.
Status check_buffer_views(GltfContext& ctx);

// What an attribute accessor may be: its type (components) and component encodings.
// With KHR_mesh_quantization in the file's extensionsUsed, `snorm` allows normalized BYTE
// and SHORT, and `integers` every 8- and 16-bit type, normalized or not (the extension's
// table: POSITION and TEXCOORD_n any, NORMAL and TANGENT normalized signed).
struct AttributeRule {
  const char* semantic;  // "POSITION"
  int components;        // 2, 3 or 4
  bool unorm8 = false;   // normalized UNSIGNED_BYTE allowed besides FLOAT
  bool unorm16 = false;  // normalized UNSIGNED_SHORT allowed besides FLOAT
  bool snorm = false;     // KHR_mesh_quantization: normalized BYTE, SHORT
  bool integers = false;  // KHR_mesh_quantization: (UNSIGNED_)BYTE, (UNSIGNED_)SHORT, any
};


// Reads accessors[index] as `rule` says into out (count * components floats, unsigned
// normalized values mapped to [0, 1]), after checking the accessor, its view and its
// byte range. `object`/`field` name the reference ("meshes[0].primitives[1]",
// "attributes.POSITION"). Non-finite values are an error.
Status read_attribute(GltfContext& ctx, int index, const AttributeRule& rule,
                      const std::string& object, const std::string& field,
                      std::vector<float>& out);

// Reads a SCALAR index accessor (UNSIGNED_BYTE / SHORT / INT, not normalized) and
// checks every value < vertex_count.
Status read_indices(GltfContext& ctx, int index, std::size_t vertex_count,
                    const std::string& object, std::vector<std::uint32_t>& out);

// A camera or light placed by a node at `world` (scale removed). `node` names the
// referencing node for errors.
Status add_camera(GltfContext& ctx, int index, const glm::dmat4& world, const std::string& node);
Status add_light(GltfContext& ctx, const tinygltf::Value& extension, const glm::dmat4& world,
                 const std::string& node);

// EXT_meshopt_compression: gives each placeholder buffer its bytes (charged to the
// budget) and decodes every compressed view into the bytes of its parent view, before
// check_buffer_views and every accessor read (GltfCompression.cpp). `model` is the
// object ctx.model refers to, the only time the loader writes to it.
Status decode_meshopt(GltfContext& ctx, tinygltf::Model& model, const GltfJsonFacts& facts);

// One primitive's KHR_draco_mesh_compression, decoded: `points` vertices, triangle
// indices (each < points), and the attributes the extension names, as floats (Draco
// dequantizes and normalizes them), every one finite.
struct DracoAttribute {
  int components = 0;
  std::vector<float> values;  // points * components
};
struct DracoGeometry {
  std::uint32_t points = 0;
  std::vector<std::uint32_t> indices;
  std::map<std::string, DracoAttribute> attributes;  // "POSITION" -> values
};
// `object` names the primitive ("meshes[0].primitives[1]"). Memory is charged first.
Status decode_draco(GltfContext& ctx, const DracoPrimitive& d, const std::string& object,
                    DracoGeometry& out);

Status convert_meshes(GltfContext& ctx);
Status convert_materials(GltfContext& ctx, const GltfJsonFacts& facts);
Status convert_nodes(GltfContext& ctx);

}  // namespace sss::scene
