// Compressed geometry: EXT_meshopt_compression (meshoptimizer's decoders, Debian's
// libmeshoptimizer-dev) and KHR_draco_mesh_compression (Google's Draco, libdraco-dev).
// Both only turn bytes into bytes or numbers. What they produce then passes the checks
// uncompressed data passes: meshopt output fills the buffer views that accessors are
// located in and range-checked against (GltfAccessor.cpp), and Draco output is counted,
// charged to the scene budget, and checked for finite values and in-range indices
// before convert_primitive uses it (GltfMesh.cpp).
#include "scene/GltfContext.h"

#include <draco/compression/decode.h>
#include <draco/core/draco_types.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstring>

namespace sss::scene {

namespace {

// Placeholders: the declared length, zero-filled, charged before it is allocated.
// check_gltf_json made sure that only compressed views refer to them, and each of those is
// filled by decode_meshopt (byteLength == count * byteStride).
Status fill_placeholders(GltfContext& ctx, tinygltf::Model& model, const GltfJsonFacts& facts) {
  for (std::size_t b = 0; b < facts.placeholder_buffers.size() && b < model.buffers.size(); ++b) {
    if (!facts.placeholder_buffers[b]) continue;
    const std::string name = indexed("buffers", b);
    // As far as its views reach (within the file's byteLength: check_gltf_json); tinygltf
    // holds the 1-byte stand-in of GltfJsonFacts::parser_json.
    std::uint64_t length = 0;
    for (std::size_t v = 0; v < facts.meshopt_views.size() && v < model.bufferViews.size(); ++v) {
      const tinygltf::BufferView& view = model.bufferViews[v];
      if (view.buffer == int(b)) length = std::max<std::uint64_t>(length, view.byteOffset + view.byteLength);
    }
    if (auto e = ctx.charge(length, name)) return e;
    model.buffers[b].data.assign(static_cast<std::size_t>(length), 0);
  }
  return std::nullopt;
}

// One view's stream decoded into `out` (sized count * stride) and its filter undone in
// place; meshoptimizer's return code (0: decoded).
int decode_meshopt_stream(const MeshoptView& m, const unsigned char* in, std::size_t in_size,
                          std::vector<unsigned char>& out) {
  const std::size_t count = static_cast<std::size_t>(m.count), stride = static_cast<std::size_t>(m.byte_stride);
  int rc = 0;
  switch (m.mode) {
    case MeshoptView::Mode::Attributes: rc = meshopt_decodeVertexBuffer(out.data(), count, stride, in, in_size); break;
    case MeshoptView::Mode::Triangles: rc = meshopt_decodeIndexBuffer(out.data(), count, stride, in, in_size); break;
    case MeshoptView::Mode::Indices: rc = meshopt_decodeIndexSequence(out.data(), count, stride, in, in_size); break;
  }
  if (rc != 0) return rc;
  switch (m.filter) {  // check_meshopt_view: the strides each filter needs
    case MeshoptView::Filter::None: break;
    case MeshoptView::Filter::Octahedral: meshopt_decodeFilterOct(out.data(), count, stride); break;
    case MeshoptView::Filter::Quaternion: meshopt_decodeFilterQuat(out.data(), count, stride); break;
    case MeshoptView::Filter::Exponential: meshopt_decodeFilterExp(out.data(), count, stride); break;
  }
  return 0;
}

}  // namespace

Status decode_meshopt(GltfContext& ctx, tinygltf::Model& model, const GltfJsonFacts& facts) {
  if (auto e = fill_placeholders(ctx, model, facts)) return e;
  std::vector<unsigned char> scratch;  // aligned for the filters, which work in place
  for (std::size_t v = 0; v < facts.meshopt_views.size() && v < model.bufferViews.size(); ++v) {
    const auto& m = facts.meshopt_views[v];
    if (!m) continue;
    const std::string name = indexed("bufferViews", v) + ".extensions.EXT_meshopt_compression";
    const tinygltf::BufferView& view = model.bufferViews[v];
    // The JSON's lengths were checked against the declared byteLengths; tinygltf's data
    // is what the loader really holds, so both ends are checked again here.
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size() ||
        m->buffer >= model.buffers.size())
      return ctx.fail(name, "buffer", "does not exist");
    const std::vector<unsigned char>& source = model.buffers[m->buffer].data;
    std::vector<unsigned char>& target = model.buffers[std::size_t(view.buffer)].data;
    if (m->byte_offset + m->byte_length > source.size())
      return ctx.fail(name, "byteLength", "runs past the " + std::to_string(source.size()) +
                                              " bytes loaded for " + indexed("buffers", m->buffer));
    const std::uint64_t decoded = m->count * m->byte_stride;  // == view.byteLength, no overflow
    if (view.byteOffset + decoded > target.size())
      return ctx.fail(indexed("bufferViews", v), "byteLength",
                      "runs past the " + std::to_string(target.size()) + " bytes of " +
                          indexed("buffers", std::size_t(view.buffer)));
    scratch.assign(static_cast<std::size_t>(decoded), 0);
    const int rc = decode_meshopt_stream(*m, source.data() + m->byte_offset,
                                         static_cast<std::size_t>(m->byte_length), scratch);
    if (rc != 0)
      return ctx.fail(name, "", "the compressed bytes do not decode (meshoptimizer returned " +
                                    std::to_string(rc) + (rc == -1 ? ": not a stream it reads" : ": malformed or truncated") + ")");
    std::memcpy(target.data() + view.byteOffset, scratch.data(), scratch.size());
  }
  return std::nullopt;
}

namespace {

// The mesh's triangles into out.indices, each index checked against out.points.
Status read_draco_faces(GltfContext& ctx, const draco::Mesh& mesh, const std::string& name, DracoGeometry& out) {
  if (auto e = ctx.charge(std::uint64_t(mesh.num_faces()) * 3 * sizeof(std::uint32_t), name)) return e;
  out.indices.resize(std::size_t(mesh.num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = mesh.face(f)[k].value();
      if (i >= out.points)
        return ctx.fail(name, "bufferView", "face " + std::to_string(f.value()) + " refers to point " +
                                                std::to_string(i) + " of " + std::to_string(out.points));
      out.indices[3 * std::size_t(f.value()) + std::size_t(k)] = i;
    }
  return std::nullopt;
}

// Draco attribute `id` (the glTF's `semantic`) as floats per point, every byte read
// checked to lie inside the attribute's buffer and every value finite.
Status read_draco_attribute(GltfContext& ctx, const draco::Mesh& mesh, const std::string& name,
                            const std::string& semantic, int id, DracoGeometry& out) {
  const draco::PointAttribute* a = mesh.GetAttributeByUniqueId(id);
  const std::string field = "attributes." + semantic;
  if (!a) return ctx.fail(name, field, "Draco attribute " + std::to_string(id) + " is not in the bitstream");
  const int n = a->num_components();
  if (n < 1 || n > 4)
    return ctx.fail(name, field, "Draco attribute " + std::to_string(id) + " has " + std::to_string(n) +
                                     " components (1 to 4 expected)");
  // Draco's ConvertValue checks only that each component starts inside the attribute's
  // buffer: the entry size, the mapping and the buffer's size are checked here first, so
  // that every byte it reads lies inside.
  const int component_bytes = draco::DataTypeLength(a->data_type());  // -1: not a type
  if (!a->buffer() || component_bytes <= 0 || a->byte_stride() < std::int64_t(n) * component_bytes ||
      a->byte_offset() != 0 || a->buffer()->data_size() / std::uint64_t(a->byte_stride()) < a->size() ||
      (!a->is_mapping_identity() && a->indices_map_size() < out.points))
    return ctx.fail(name, field, "Draco attribute " + std::to_string(id) + " is inconsistent with its data");
  if (auto e = ctx.charge(std::uint64_t(out.points) * std::uint64_t(n) * sizeof(float), name)) return e;
  DracoAttribute& attribute = out.attributes[semantic];
  attribute.components = n;
  std::vector<float>& values = attribute.values;
  values.resize(std::size_t(out.points) * std::size_t(n));
  for (std::uint32_t p = 0; p < out.points; ++p) {
    float* v = values.data() + std::size_t(p) * std::size_t(n);
    const draco::AttributeValueIndex at = a->mapped_index(draco::PointIndex(p));
    if (at.value() >= a->size() || !a->ConvertValue<float>(at, static_cast<int8_t>(n), v))
      return ctx.fail(name, field, "Draco attribute " + std::to_string(id) + " point " + std::to_string(p) +
                                       " cannot be read as numbers");
    for (int c = 0; c < n; ++c)
      if (!std::isfinite(v[c]))
        return ctx.fail(name, field, "point " + std::to_string(p) + " component " + std::to_string(c) + " is " +
                                         number_text(v[c]) + "; values must be finite");
  }
  return std::nullopt;
}

}  // namespace

Status decode_draco(GltfContext& ctx, const DracoPrimitive& d, const std::string& object,
                    DracoGeometry& out) {
  const std::string name = object + ".extensions.KHR_draco_mesh_compression";
  if (auto e = out_of_range("bufferViews", static_cast<long long>(d.buffer_view), ctx.model.bufferViews.size()))
    return ctx.fail(name, "bufferView", *e);
  const tinygltf::BufferView& view = ctx.model.bufferViews[d.buffer_view];
  const auto& bytes = ctx.model.buffers[std::size_t(view.buffer)].data;  // check_buffer_views: in range
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data() + view.byteOffset), view.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    return ctx.fail(name, "bufferView", "the Draco bitstream does not decode: " + decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) return ctx.fail(name, "bufferView", "the Draco bitstream holds no mesh");
  out.points = mesh->num_points();
  if (auto e = read_draco_faces(ctx, *mesh, name, out)) return e;
  for (const auto& [semantic, id] : d.attributes)
    if (auto e = read_draco_attribute(ctx, *mesh, name, semantic, id, out)) return e;
  return std::nullopt;
}

}  // namespace sss::scene
