// Materials, textures, samplers and images. Images are decoded only when a material
// uses them, only after their bytes were checked, and only as PNG or JPEG.
#include "scene/GltfContext.h"

#include <cmath>
#include <span>

namespace sss::scene {

namespace {

Status check_unit_interval(GltfContext& ctx, const std::string& object, const std::string& field,
                           double v) {
  if (std::isfinite(v) && v >= 0.0 && v <= 1.0) return std::nullopt;
  return ctx.fail(object, field, "must lie in [0, 1], got " + number_text(v));
}

Status decode(GltfContext& ctx, int index, std::shared_ptr<const ImageRgba8>& out) {
  const std::size_t i = std::size_t(index);
  if (ctx.images[i]) {
    out = ctx.images[i];
    return std::nullopt;
  }
  const tinygltf::Image& img = ctx.model.images[i];
  const std::string object = indexed("images", i);
  std::span<const unsigned char> bytes;
  const char* field = "uri";
  if (img.bufferView >= 0) {
    field = "bufferView";
    if (auto e = out_of_range("bufferViews", img.bufferView, ctx.model.bufferViews.size()))
      return ctx.fail(object, field, *e);
    const tinygltf::BufferView& v = ctx.model.bufferViews[std::size_t(img.bufferView)];
    // check_buffer_views() has put [byteOffset, byteOffset + byteLength) inside the buffer.
    bytes = std::span<const unsigned char>(
        ctx.model.buffers[std::size_t(v.buffer)].data.data() + v.byteOffset, v.byteLength);
  } else if (i < ctx.uri_image_bytes.size()) {
    bytes = ctx.uri_image_bytes[i];
  }
  if (bytes.empty()) return ctx.fail(object, field, "has no image data");
  // The bytes must be what the file says they are (a PNG declared as JPEG is a broken
  // or crafted file); decode_image then refuses anything but PNG and JPEG.
  const std::string_view sniffed = image_media_type(bytes);
  const std::string& declared = i < ctx.image_media_type.size() ? ctx.image_media_type[i] : std::string();
  if (!declared.empty() && !sniffed.empty() && sniffed != declared)
    return ctx.fail(object, img.bufferView >= 0 ? "mimeType" : field,
                    "declares " + declared + " but the bytes are " + std::string(sniffed));
  ImageLimits limits = ctx.options.image_limits;
  const std::uint64_t left = ctx.options.max_scene_bytes - ctx.bytes_charged;
  limits.max_pixels = std::min(limits.max_pixels, left / 4);
  auto decoded = decode_image(bytes, limits);
  if (auto* msg = std::get_if<std::string>(&decoded)) return ctx.fail(object, field, *msg);
  auto& image = std::get<ImageRgba8>(decoded);
  if (auto e = ctx.charge(image.pixels.size(), object)) return e;
  image.name = img.name.empty() ? object : img.name;
  ctx.images[i] = std::make_shared<const ImageRgba8>(std::move(image));
  out = ctx.images[i];
  return std::nullopt;
}

// The scene texture for glTF textures[index], converting it on first use.
Status texture(GltfContext& ctx, int index, const std::string& object, const std::string& field,
               std::optional<std::uint32_t>& out) {
  if (auto e = out_of_range("textures", index, ctx.model.textures.size()))
    return ctx.fail(object, field, *e);
  const std::size_t t = std::size_t(index);
  if (ctx.texture_map[t]) {
    out = ctx.texture_map[t];
    return std::nullopt;
  }
  const tinygltf::Texture& gt = ctx.model.textures[t];
  const std::string name = indexed("textures", t);
  if (gt.source < 0)
    return ctx.fail(name, "source", "is missing (image extensions such as KHR_texture_basisu "
                                    "are not supported)");
  if (auto e = out_of_range("images", gt.source, ctx.model.images.size()))
    return ctx.fail(name, "source", *e);
  Texture tex;
  tex.name = gt.name.empty() ? name : gt.name;
  if (gt.sampler >= 0) {
    if (auto e = out_of_range("samplers", gt.sampler, ctx.model.samplers.size()))
      return ctx.fail(name, "sampler", *e);
    const tinygltf::Sampler& s = ctx.model.samplers[std::size_t(gt.sampler)];
    const auto sampler = sampler_from_gl(s.magFilter, s.minFilter, s.wrapS, s.wrapT);
    if (!sampler)
      return ctx.fail(indexed("samplers", std::size_t(gt.sampler)), "",
                      "has a filter or wrap value that is not a glTF enum (magFilter " +
                          std::to_string(s.magFilter) + ", minFilter " + std::to_string(s.minFilter) +
                          ", wrapS " + std::to_string(s.wrapS) + ", wrapT " + std::to_string(s.wrapT) + ")");
    tex.sampler = *sampler;
  }
  if (auto e = decode(ctx, gt.source, tex.image)) return e;
  out = static_cast<std::uint32_t>(ctx.scene.textures.size());
  ctx.texture_map[t] = out;
  ctx.scene.textures.push_back(std::move(tex));
  return std::nullopt;
}

// A material's texture reference; a texture set other than 0 is dropped with a warning.
using UvTransform = std::array<float, 6>;

// KHR_texture_transform on a texture reference (its README): uv' = T R S uv with
// T = [1 0 ox; 0 1 oy], R = [cos r, sin r; -sin r, cos r], S = diag(sx, sy); its
// texCoord replaces the reference's. Values must be finite.
Status texture_transform(GltfContext& ctx, const tinygltf::ExtensionMap& extensions,
                         const std::string& object, const std::string& field, int& tex_coord,
                         std::optional<UvTransform>& out) {
  const auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end()) return std::nullopt;
  const tinygltf::Value& t = it->second;
  const std::string where = field + ".extensions.KHR_texture_transform";
  if (!t.IsObject()) return ctx.fail(object, where, "must be an object");
  const auto vec2 = [&](const char* key, double x, double y, double& ox, double& oy) -> Status {
    ox = x;
    oy = y;
    if (!t.Has(key)) return std::nullopt;
    const tinygltf::Value& v = t.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
      return ctx.fail(object, where + "." + key, "must be an array of 2 numbers");
    ox = v.Get(0).GetNumberAsDouble();
    oy = v.Get(1).GetNumberAsDouble();
    if (!std::isfinite(ox) || !std::isfinite(oy) || std::fabs(ox) > 1e30 || std::fabs(oy) > 1e30)
      return ctx.fail(object, where + "." + key, "must be finite numbers");
    return std::nullopt;
  };
  double ox = 0, oy = 0, sx = 1, sy = 1, r = 0;
  if (auto e = vec2("offset", 0.0, 0.0, ox, oy)) return e;
  if (auto e = vec2("scale", 1.0, 1.0, sx, sy)) return e;
  if (t.Has("rotation")) {
    const tinygltf::Value& v = t.Get("rotation");
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()) || std::fabs(v.GetNumberAsDouble()) > 1e6)
      return ctx.fail(object, where + ".rotation", "must be a finite number of radians");
    r = v.GetNumberAsDouble();
  }
  if (t.Has("texCoord")) {
    const tinygltf::Value& v = t.Get("texCoord");
    if (!v.IsInt() || v.GetNumberAsInt() < 0)
      return ctx.fail(object, where + ".texCoord", "must be an integer >= 0");
    tex_coord = v.GetNumberAsInt();
  }
  const double c = std::cos(r), s = std::sin(r);
  out = UvTransform{float(c * sx), float(s * sy), float(ox), float(-s * sx), float(c * sy), float(oy)};
  return std::nullopt;
}

Status texture_ref(GltfContext& ctx, int index, int tex_coord, const std::string& object,
                   const std::string& field, std::optional<std::uint32_t>& out) {
  if (index < 0) return std::nullopt;
  if (tex_coord != 0) {
    ctx.scene.warnings.push_back(ctx.file + ": " + object + "." + field + ": uses TEXCOORD_" +
                                 std::to_string(tex_coord) + "; only TEXCOORD_0 is read, texture ignored");
    return std::nullopt;
  }
  return texture(ctx, index, object, field + ".index", out);
}

}  // namespace

namespace {

// The metallic-roughness factors: base colour, metallic, roughness, each in [0, 1].
Status read_factors(GltfContext& ctx, const tinygltf::Material& gm, const std::string& object, Material& m) {
  const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() != 4)
    return ctx.fail(object, "pbrMetallicRoughness.baseColorFactor", "must have 4 numbers");
  for (int c = 0; c < 4; ++c) {
    if (auto e = check_unit_interval(ctx, object,
                                     "pbrMetallicRoughness.baseColorFactor[" + std::to_string(c) + "]",
                                     pbr.baseColorFactor[std::size_t(c)]))
      return e;
    m.base_color[c] = static_cast<float>(pbr.baseColorFactor[std::size_t(c)]);
  }
  if (auto e = check_unit_interval(ctx, object, "pbrMetallicRoughness.metallicFactor", pbr.metallicFactor))
    return e;
  if (auto e = check_unit_interval(ctx, object, "pbrMetallicRoughness.roughnessFactor", pbr.roughnessFactor))
    return e;
  m.metallic = static_cast<float>(pbr.metallicFactor);
  m.roughness = static_cast<float>(pbr.roughnessFactor);
  return std::nullopt;
}

// The base colour and normal textures of material i, their KHR_texture_transform (one per
// material, ctx.uv_transforms[i]) and the normal scale.
Status read_textures(GltfContext& ctx, const tinygltf::Material& gm, std::size_t i, const std::string& object,
                     Material& m) {
  const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
  // KHR_texture_transform: the renderer reads both textures through one TEXCOORD_0, so
  // the transform is applied to the material's UVs (convert_meshes); where the two
  // textures' transforms differ, the base colour's is used and a warning says so.
  int base_coord = pbr.baseColorTexture.texCoord, normal_coord = gm.normalTexture.texCoord;
  std::optional<UvTransform> base_tf, normal_tf;
  if (pbr.baseColorTexture.index >= 0)
    if (auto e = texture_transform(ctx, pbr.baseColorTexture.extensions, object,
                                   "pbrMetallicRoughness.baseColorTexture", base_coord, base_tf))
      return e;
  if (gm.normalTexture.index >= 0)
    if (auto e = texture_transform(ctx, gm.normalTexture.extensions, object, "normalTexture",
                                   normal_coord, normal_tf))
      return e;
  if (auto e = texture_ref(ctx, pbr.baseColorTexture.index, base_coord, object,
                           "pbrMetallicRoughness.baseColorTexture", m.base_color_texture))
    return e;
  if (auto e = texture_ref(ctx, gm.normalTexture.index, normal_coord, object,
                           "normalTexture", m.normal_texture))
    return e;
  if (!m.base_color_texture) base_tf.reset();
  if (!m.normal_texture) normal_tf.reset();
  const UvTransform identity{1, 0, 0, 0, 1, 0};
  const UvTransform tb = base_tf.value_or(identity), tn = normal_tf.value_or(identity);
  bool same = true;
  for (int k = 0; k < 6; ++k) same = same && std::fabs(tb[k] - tn[k]) <= 1e-6f * (1.0f + std::fabs(tb[k]));
  if (m.base_color_texture && m.normal_texture && !same)
    ctx.scene.warnings.push_back(ctx.file + ": " + object +
                                 ": the base colour and normal textures have different "
                                 "KHR_texture_transform; both are drawn with the base colour's");
  ctx.uv_transforms[i] = m.base_color_texture ? base_tf : normal_tf;
  if (!std::isfinite(gm.normalTexture.scale) || std::fabs(gm.normalTexture.scale) > 1e6)
    return ctx.fail(object, "normalTexture.scale",
                    "must be a finite number, got " + number_text(gm.normalTexture.scale));
  m.normal_scale = static_cast<float>(gm.normalTexture.scale);
  return std::nullopt;
}

// Material i's medium: extras.sss, else the KHR volume and scatter extensions' (with their
// notes), the KHR ior's specular, and what of KHR was not read. `both` collects materials
// that have extras.sss and a KHR scatter extension.
void read_medium(GltfContext& ctx, const GltfJsonFacts& facts, std::size_t i, const std::string& object, Material& m,
                 std::vector<std::string>& both) {
  const std::optional<KhrMedium>& khr = facts.material_khr[i];
  if (facts.material_sss[i]) {
    m.sss = *facts.material_sss[i];
    if (khr && khr->scatter != KhrMedium::Scatter::None) both.push_back(object);
  } else if (khr) {
    std::string why_not;
    if (auto sss = khr_sss_material(*khr, ctx.options.mm_per_unit, why_not)) {
      m.sss = std::move(*sss);
      for (const std::string& note : khr_transmission_notes(*khr))
        ctx.scene.warnings.push_back(ctx.file + ": " + object + ": " + note);
    }
    if (!why_not.empty()) ctx.scene.warnings.push_back(ctx.file + ": " + object + ": " + why_not);
  }
  if (khr && khr->ior && *khr->ior >= 1.0) m.specular = float(ior_f0(*khr->ior) / 0.04);  // F0 = 0.04 specular
  if (khr && !khr->ignored.empty()) {
    std::string list;
    for (const std::string& f : khr->ignored) list += (list.empty() ? "" : ", ") + f;
    ctx.scene.warnings.push_back(ctx.file + ": " + object + ": not read (the medium is one per material): " + list);
  }
}

}  // namespace

Status convert_materials(GltfContext& ctx, const GltfJsonFacts& facts) {
  const auto& materials = ctx.model.materials;
  if (facts.material_count != materials.size())
    return ctx.fail("materials", "", "tinygltf read " + std::to_string(materials.size()) +
                                         " materials where the JSON has " +
                                         std::to_string(facts.material_count));
  ctx.texture_map.assign(ctx.model.textures.size(), std::nullopt);
  ctx.images.assign(ctx.model.images.size(), nullptr);
  ctx.uv_transforms.assign(materials.size(), std::nullopt);
  std::vector<std::string> both;  // materials with extras.sss and a KHR scatter extension
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const tinygltf::Material& gm = materials[i];
    const std::string object = indexed("materials", i);
    Material m;
    m.name = gm.name.empty() ? object : gm.name;
    if (auto e = read_factors(ctx, gm, object, m)) return e;
    if (auto e = read_textures(ctx, gm, i, object, m)) return e;
    m.double_sided = gm.doubleSided;
    read_medium(ctx, facts, i, object, m, both);
    ctx.scene.materials.push_back(std::move(m));
  }
  if (!both.empty()) {
    std::string list;
    for (const std::string& o : both) list += (list.empty() ? "" : ", ") + o;
    ctx.scene.warnings.push_back(ctx.file + ": " + list + ": extras.sss and a KHR scatter extension "
                                 "both describe the medium; extras.sss is used");
  }
  return std::nullopt;
}

}  // namespace sss::scene
