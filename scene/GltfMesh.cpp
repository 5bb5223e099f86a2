// Meshes: each glTF primitive becomes one scene Mesh with uint32 triangle indices and
// unit normals.
#include "scene/GltfContext.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>

namespace sss::scene {

namespace {

// KHR_mesh_quantization's table of what each attribute may be (its README, "Extending
// Mesh Attributes").
constexpr AttributeRule kPosition{"POSITION", 3, false, false, true, true};
constexpr AttributeRule kNormal{"NORMAL", 3, false, false, true, false};
constexpr AttributeRule kTexcoord{"TEXCOORD_0", 2, true, true, true, true};
constexpr AttributeRule kTangent{"TANGENT", 4, false, false, true, false};

// Triangle list from a strip or fan of `seq` (glTF 2.0 §3.7.2.1 winding).
std::vector<std::uint32_t> to_triangles(const std::vector<std::uint32_t>& seq, int mode) {
  std::vector<std::uint32_t> tri;
  if (seq.size() < 3) return tri;
  tri.reserve(3 * (seq.size() - 2));
  for (std::size_t i = 0; i + 2 < seq.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      const bool odd = i % 2 == 1;
      tri.insert(tri.end(), {seq[i], seq[i + (odd ? 2 : 1)], seq[i + (odd ? 1 : 2)]});
    } else {  // fan
      tri.insert(tri.end(), {seq[i + 1], seq[i + 2], seq[0]});
    }
  }
  return tri;
}

Status attribute_count(GltfContext& ctx, const std::string& object, const char* semantic,
                       std::size_t got, std::size_t expected) {
  if (got == expected) return std::nullopt;
  return ctx.fail(object, std::string("attributes.") + semantic,
                  "has " + std::to_string(got) + " elements but POSITION has " +
                      std::to_string(expected));
}

// The file's tangents follow its UVs, ∂P/∂u. Where KHR_texture_transform maps (u, v) to
// (u', v') = M (u, v) + o, the normal map is sampled along u', so the tangent becomes
// ∂P/∂u' = (M⁻¹)₀₀ ∂P/∂u + (M⁻¹)₁₀ ∂P/∂v, and the handedness follows ∂P/∂v'. The
// file's tangent and bitangent (w · N × T) are unit, so this takes |∂P/∂u| = |∂P/∂v|:
// exact for a scale and offset (the direction does not change) and for a rotation of a
// conformal mapping. A singular M (a zero scale) leaves no direction: tangents dropped.
// Without normals the tangents are dropped too, as the spec asks.
Status transform_tangents(GltfContext& ctx, const tinygltf::Primitive& prim, const std::string& object,
                          Mesh& mesh) {
  if (mesh.normals.empty()) {  // glTF 2.0 §3.7.2.1: without normals, tangents MUST be ignored
    mesh.tangents.clear();
    return std::nullopt;
  }
  if (mesh.normals.size() != mesh.tangents.size() || prim.material < 0 ||
      std::size_t(prim.material) >= ctx.uv_transforms.size() || !ctx.uv_transforms[std::size_t(prim.material)])
    return std::nullopt;
  const auto& t = *ctx.uv_transforms[std::size_t(prim.material)];
  if (t[1] == 0.0f && t[3] == 0.0f && t[0] > 0.0f && t[4] > 0.0f) return std::nullopt;  // scale and offset
  const float det = t[0] * t[4] - t[1] * t[3];
  if (!(std::abs(det) > 0.0f) || !std::isfinite(1.0f / det)) {
    ctx.scene.warnings.push_back(ctx.file + ": " + object + ": KHR_texture_transform of materials[" +
                                 std::to_string(prim.material) + "] is singular; its tangents are dropped");
    mesh.tangents.clear();
    return std::nullopt;
  }
  const float i00 = t[4] / det, i01 = -t[1] / det, i10 = -t[3] / det, i11 = t[0] / det;
  for (std::size_t i = 0; i < mesh.tangents.size(); ++i) {
    const glm::vec3 n = mesh.normals[i];
    const glm::vec3 tu(mesh.tangents[i]);
    const glm::vec3 tv = mesh.tangents[i].w * glm::cross(n, tu);
    const glm::vec3 du = i00 * tu + i10 * tv, dv = i01 * tu + i11 * tv;
    const float len = glm::length(du);
    if (!(len > 0.0f) || !std::isfinite(len)) continue;  // a zero normal: keep the file's
    mesh.tangents[i] = glm::vec4(du / len, glm::dot(glm::cross(n, du), dv) < 0.0f ? -1.0f : 1.0f);
  }
  return std::nullopt;
}

// A primitive's attributes: from the Draco bitstream where it names them, else from
// their accessors.
struct AttributeSource {
  GltfContext& ctx;
  const tinygltf::Primitive& prim;
  const DracoGeometry& draco;
  const std::string& object;

  // The accessor of attributes.SEMANTIC, or -1.
  int accessor(const char* semantic) const {
    const auto it = prim.attributes.find(semantic);
    return it == prim.attributes.end() ? -1 : it->second;
  }
  // attributes.SEMANTIC as `rule` says.
  Status read(const AttributeRule& rule, std::vector<float>& out) const {
    const std::string field = std::string("attributes.") + rule.semantic;
    const auto it = draco.attributes.find(rule.semantic);
    if (it == draco.attributes.end()) return read_attribute(ctx, accessor(rule.semantic), rule, object, field, out);
    if (it->second.components != rule.components)
      return ctx.fail(object + ".extensions.KHR_draco_mesh_compression", field,
                      "decodes to " + std::to_string(it->second.components) + " components; " +
                          rule.semantic + " has " + std::to_string(rule.components));
    out = it->second.values;
    return std::nullopt;
  }
};

// POSITION, NORMAL, TEXCOORD_0 (with KHR_texture_transform) and TANGENT into `mesh`; the
// vertex count in `n`.
// KHR_texture_transform of the material's textures, applied to the UVs they read.
Status transform_uvs(GltfContext& ctx, const tinygltf::Primitive& prim, const std::string& object,
                     Mesh& mesh) {
  if (!mesh.uv0.empty() && prim.material >= 0 && std::size_t(prim.material) < ctx.uv_transforms.size())
    if (const auto& t = ctx.uv_transforms[std::size_t(prim.material)])
      for (glm::vec2& uv : mesh.uv0) {
        const float u = uv.x, v = uv.y;
        uv = {(*t)[0] * u + (*t)[1] * v + (*t)[2], (*t)[3] * u + (*t)[4] * v + (*t)[5]};
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
          return ctx.fail(object, "attributes.TEXCOORD_0",
                          "KHR_texture_transform of materials[" + std::to_string(prim.material) +
                              "] takes a UV past float range");
      }
  return std::nullopt;
}

// TANGENT, normalized, with w made +1 or -1, then following the UVs' KHR_texture_transform.
Status read_tangents(const AttributeSource& source, Mesh& mesh, std::size_t n) {
  GltfContext& ctx = source.ctx;
  const std::string& object = source.object;
  std::vector<float> f;
  if (auto e = source.read(kTangent, f)) return e;
  if (auto e = attribute_count(ctx, object, "TANGENT", f.size() / 4, n)) return e;
  mesh.tangents.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const float w = f[4 * i + 3];
    if (w == 0.0f)
      return ctx.fail(object, "attributes.TANGENT", "element " + std::to_string(i) +
                                                        " has w = 0; it must be +1 or -1");
    glm::vec3 t(f[4 * i], f[4 * i + 1], f[4 * i + 2]);
    const float len = glm::length(t);
    t = len > 0.0f && std::isfinite(len) ? t / len : glm::vec3(1, 0, 0);
    mesh.tangents[i] = glm::vec4(t, w > 0.0f ? 1.0f : -1.0f);
  }
  if (auto e = transform_tangents(ctx, source.prim, object, mesh)) return e;
  return std::nullopt;
}

Status read_vertices(const AttributeSource& source, bool compressed, Mesh& mesh, std::size_t& n) {
  GltfContext& ctx = source.ctx;
  const tinygltf::Primitive& prim = source.prim;
  const DracoGeometry& draco = source.draco;
  const std::string& object = source.object;
  const auto attr = [&](const char* s) { return source.accessor(s); };
  const auto read = [&](const AttributeRule& rule, std::vector<float>& out) { return source.read(rule, out); };
  std::vector<float> f;
  if (auto e = read(kPosition, f)) return e;
  n = f.size() / 3;
  if (n > std::numeric_limits<std::uint32_t>::max())
    return ctx.fail(object, "attributes.POSITION", "too many vertices for 32-bit indices");
  if (compressed && n != draco.points)  // Draco's indices count its points
    return ctx.fail(object, "attributes.POSITION", "has " + std::to_string(n) +
                                                       " elements but the Draco bitstream has " +
                                                       std::to_string(draco.points) + " points");
  // Every attribute has as many elements as POSITION (glTF 2.0 §3.7.2.1), also those not
  // read here (COLOR_0, JOINTS_0, ...): their indices were checked by check_gltf_schema.
  for (const auto& [semantic, accessor] : prim.attributes) {
    if (auto e = out_of_range("accessors", accessor, ctx.model.accessors.size()))
      return ctx.fail(object, "attributes." + semantic, *e);
    if (auto e = attribute_count(ctx, object, semantic.c_str(),
                                 ctx.model.accessors[std::size_t(accessor)].count, n))
      return e;
  }
  mesh.positions.resize(n);
  for (std::size_t i = 0; i < n; ++i) mesh.positions[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  if (attr("NORMAL") >= 0) {
    if (auto e = read(kNormal, f)) return e;
    if (auto e = attribute_count(ctx, object, "NORMAL", f.size() / 3, n)) return e;
    mesh.normals.resize(n);
    for (std::size_t i = 0; i < n; ++i) mesh.normals[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
    // Quantized normals are unit only to their precision (1/127 for BYTE; Draco's
    // octahedral quantization).
    if (draco.attributes.count("NORMAL") ||
        ctx.model.accessors[std::size_t(attr("NORMAL"))].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
      for (glm::vec3& v : mesh.normals) {
        const float len = glm::length(v);
        if (len > 0.0f) v /= len;
      }
  }
  if (attr("TEXCOORD_0") >= 0) {
    if (auto e = read(kTexcoord, f)) return e;
    if (auto e = attribute_count(ctx, object, "TEXCOORD_0", f.size() / 2, n)) return e;
    mesh.uv0.resize(n);
    for (std::size_t i = 0; i < n; ++i) mesh.uv0[i] = {f[2 * i], f[2 * i + 1]};
  }
  if (auto e = transform_uvs(ctx, prim, object, mesh)) return e;
  if (attr("TANGENT") >= 0)
    if (auto e = read_tangents(source, mesh, n)) return e;
  return std::nullopt;
}

// The index sequence (Draco's, the accessor's, or 0..n-1) as triangles (strips and fans
// unrolled) into mesh.indices.
Status read_triangles(GltfContext& ctx, const tinygltf::Primitive& prim, int mode, std::size_t n,
                      const std::optional<DracoPrimitive>* draco_ext, DracoGeometry& draco,
                      const std::string& object, Mesh& mesh) {
  const bool compressed = draco_ext && draco_ext->has_value();
  std::vector<std::uint32_t> seq;
  if (compressed) {
    // check_gltf_schema: the index exists.
    if (const auto i = (*draco_ext)->indices; i && ctx.model.accessors[*i].count != draco.indices.size())
      return ctx.fail(object, "indices",
                      indexed("accessors", *i) + " has " + std::to_string(ctx.model.accessors[*i].count) +
                          " elements but the Draco bitstream decodes " + std::to_string(draco.indices.size()));
    seq = std::move(draco.indices);
  } else if (prim.indices >= 0) {
    if (auto e = read_indices(ctx, prim.indices, n, object, seq)) return e;
  } else {
    if (auto e = ctx.charge(n * sizeof(std::uint32_t), object)) return e;
    seq = sequential_indices(static_cast<std::uint32_t>(n));
  }
  const char* what = prim.indices >= 0 || compressed ? "indices" : "attributes.POSITION";
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (seq.size() % 3 != 0)
      return ctx.fail(object, what, std::to_string(seq.size()) +
                                        " vertices do not make whole triangles (a multiple of 3)");
    mesh.indices = std::move(seq);
  } else {
    if (seq.size() < 3)
      return ctx.fail(object, what, "a strip or fan needs at least 3 vertices");
    if (auto e = ctx.charge(3 * seq.size() * sizeof(std::uint32_t), object)) return e;
    mesh.indices = to_triangles(seq, mode);
  }
  if (mesh.indices.empty()) return ctx.fail(object, what, "has no triangles");
  return std::nullopt;
}

// The primitive's material, or the glTF default one (made once per file).
Status assign_material(GltfContext& ctx, const tinygltf::Primitive& prim, const std::string& object,
                       std::optional<std::uint32_t>& default_material, Mesh& mesh) {
  if (prim.material >= 0) {
    if (auto e = out_of_range("materials", prim.material, ctx.model.materials.size()))
      return ctx.fail(object, "material", *e);
    mesh.material = static_cast<std::uint32_t>(prim.material);
  } else {
    if (!default_material) {
      default_material = static_cast<std::uint32_t>(ctx.scene.materials.size());
      Material def;
      def.name = "default";  // glTF 2.0 §3.9.6: white, metallic 1, roughness 1
      ctx.scene.materials.push_back(def);
    }
    mesh.material = *default_material;
  }
  return std::nullopt;
}

Status convert_primitive(GltfContext& ctx, std::size_t m, std::size_t p,
                         std::optional<std::uint32_t>& default_material) {
  const tinygltf::Mesh& gm = ctx.model.meshes[m];
  const tinygltf::Primitive& prim = gm.primitives[p];
  const std::string object = indexed("meshes", m) + "." + indexed("primitives", p);
  const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;  // -1: not given
  if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN)
    return ctx.fail(object, "mode", std::to_string(prim.mode) + " is not a glTF primitive mode (0..6)");
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    ctx.scene.warnings.push_back(ctx.file + ": " + object + ": mode " + std::to_string(mode) +
                                 " (points or lines) skipped; only triangles scatter light");
    return std::nullopt;
  }
  if (!prim.targets.empty())
    ctx.scene.warnings.push_back(ctx.file + ": " + object + ": morph targets ignored");

  Mesh mesh;
  mesh.name = gm.name.empty() ? indexed("meshes", m) : gm.name;
  if (gm.primitives.size() > 1) mesh.name += "/" + std::to_string(p);
  if (prim.attributes.find("POSITION") == prim.attributes.end())
    return ctx.fail(object, "attributes.POSITION", "is required");
  // KHR_draco_mesh_compression: the attributes it names and the indices come from the
  // bitstream; the primitive's other attributes are read as usual (its README).
  const std::optional<DracoPrimitive>* draco_ext =
      m < ctx.draco.size() && p < ctx.draco[m].size() ? &ctx.draco[m][p] : nullptr;
  const bool compressed = draco_ext && draco_ext->has_value();
  DracoGeometry draco;
  if (compressed) {
    if (mode != TINYGLTF_MODE_TRIANGLES)
      return ctx.fail(object, "mode", "must be 4 (triangles) with KHR_draco_mesh_compression");
    if (auto e = decode_draco(ctx, **draco_ext, object, draco)) return e;
  }
  std::size_t n = 0;
  if (auto e = read_vertices({ctx, prim, draco, object}, compressed, mesh, n)) return e;
  if (auto e = read_triangles(ctx, prim, mode, n, draco_ext, draco, object, mesh)) return e;
  if (auto e = assign_material(ctx, prim, object, default_material, mesh)) return e;
  if (auto e = ctx.charge(n * sizeof(glm::vec3), object)) return e;  // generated normals
  if (const std::size_t replaced = repair_normals(mesh))
    ctx.scene.warnings.push_back(ctx.file + ": " + object + ": " + std::to_string(replaced) +
                                 " zero-length normals replaced by generated ones");
  compute_bounds(mesh);
  if (auto problem = check_mesh(mesh)) return ctx.fail(object, "", *problem);
  ctx.mesh_primitives[m].push_back(static_cast<std::uint32_t>(ctx.scene.meshes.size()));
  ctx.scene.meshes.push_back(std::move(mesh));
  return std::nullopt;
}

}  // namespace

Status convert_meshes(GltfContext& ctx) {
  ctx.mesh_primitives.assign(ctx.model.meshes.size(), {});
  std::optional<std::uint32_t> default_material;
  for (std::size_t m = 0; m < ctx.model.meshes.size(); ++m) {
    if (ctx.model.meshes[m].primitives.empty())
      return ctx.fail(indexed("meshes", m), "primitives", "must not be empty");
    for (std::size_t p = 0; p < ctx.model.meshes[m].primitives.size(); ++p)
      if (auto e = convert_primitive(ctx, m, p, default_material)) return e;
  }
  return std::nullopt;
}

}  // namespace sss::scene
