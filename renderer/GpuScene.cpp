#include "renderer/GpuScene.h"

#include "renderer/CameraSetup.h"
#include "reference/SkyOcclusion.h"
#include "reference/Thickness.h"
#include "scene/UvAtlas.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/GraphicsPipeline.h"
#include "renderer/vk/Sampler.h"
#include "renderer/vk/Transfer.h"
#include "shaders/shared/frame.h"

#include <chrono>
#include <cstddef>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

namespace sss::renderer {

namespace {

VkSamplerAddressMode address(scene::Wrap w) {
  switch (w) {
    case scene::Wrap::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case scene::Wrap::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case scene::Wrap::Repeat: break;
  }
  return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

vk::Image upload_rgba8(const vk::Context& context, std::uint32_t w, std::uint32_t h,
                       std::span<const std::uint8_t> pixels, bool srgb, const std::string& name) {
  vk::Image image(context, {w, h, srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM,
                            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, name});
  vk::upload_image(context, image, std::as_bytes(pixels), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  return image;
}

}  // namespace

void add_vertex_input(vk::GraphicsPipelineBuilder& builder) {
  builder.vertex_binding(0, sizeof(GpuVertex))
      .vertex_attribute(0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, position))
      .vertex_attribute(1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, normal))
      .vertex_attribute(2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(GpuVertex, uv))
      .vertex_attribute(3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(GpuVertex, tangent))
      .vertex_attribute(4, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(GpuVertex, atlas))
      .vertex_attribute(5, 0, VK_FORMAT_R32_SFLOAT, offsetof(GpuVertex, thickness));
}

void add_sky_vertex_input(vk::GraphicsPipelineBuilder& builder) {
  static_assert(sizeof(reference::SkyTransfer) == 9 * sizeof(float));
  builder.vertex_binding(1, sizeof(reference::SkyTransfer));
  for (std::uint32_t k = 0; k < 3; ++k)
    builder.vertex_attribute(6 + k, 1, VK_FORMAT_R32G32B32_SFLOAT, 3 * k * sizeof(float));
}

int GpuScene::add_texture(const vk::Context& context, const scene::Scene& scene,
                          std::uint32_t texture, bool srgb) {
  if (texture >= scene.textures.size() || !scene.textures[texture].image) return -1;
  if (slots_.size() >= shader::kMaxTextures) {
    warnings_.push_back("texture '" + scene.textures[texture].name + "' ignored: at most " +
                        std::to_string(shader::kMaxTextures - 1) + " textures are bound");
    return -1;
  }
  const scene::Texture& t = scene.textures[texture];
  Slot slot;
  slot.image = upload_rgba8(context, t.image->width, t.image->height, t.image->pixels, srgb,
                            t.name);
  vk::SamplerDesc desc(t.sampler.mag == scene::Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR,
                       VK_SAMPLER_MIPMAP_MODE_NEAREST, address(t.sampler.wrap_s));
  desc.name = t.name;
  slot.sampler = vk::create_sampler(context, desc);
  slots_.push_back(std::move(slot));
  return static_cast<int>(slots_.size()) - 1;
}

GpuScene::GpuScene(const vk::Context& context, const scene::Scene& scene)
    : instances_(scene.instances), materials_(scene.materials), mm_per_unit_(scene.mm_per_unit) {
  geometry_.mm_per_unit = scene.mm_per_unit;
  geometry_.instances = scene.instances;
  for (const scene::Mesh& mesh : scene.meshes) {
    scene::Mesh& m = geometry_.meshes.emplace_back();
    m.name = mesh.name;
    m.positions = mesh.positions;
    m.normals = mesh.normals;
    m.indices = mesh.indices;
  }
  // Slot 0: white, bound wherever a slot is unused.
  const std::uint8_t white[4] = {255, 255, 255, 255};
  Slot dummy;
  dummy.image = upload_rgba8(context, 1, 1, white, false, "white");
  dummy.sampler = vk::create_sampler(context, {});
  slots_.push_back(std::move(dummy));

  std::map<std::pair<std::uint32_t, bool>, int> slot_of;  // (texture, srgb) -> slot
  const auto slot_for = [&](std::uint32_t texture, bool srgb) {
    const auto key = std::make_pair(texture, srgb);
    auto it = slot_of.find(key);
    if (it == slot_of.end()) it = slot_of.emplace(key, add_texture(context, scene, texture, srgb)).first;
    return it->second;
  };

  for (const scene::Mesh& mesh : scene.meshes) {
    const bool has_uv = mesh.uv0.size() == mesh.positions.size();
    const bool has_tangents = mesh.tangents.size() == mesh.positions.size();
    const bool scatters =
        mesh.material < scene.materials.size() && scene.materials[mesh.material].sss.enabled;
    MeshBuffers b = upload_geometry(context, mesh, scatters);
    // A mesh without SSS UVs: kept to build its atlas when texture-space SSS needs it
    // (ensure_sss_uvs: its material scatters, now or once the live renderer says so).
    deferred_.push_back(b.sss_uvs ? std::nullopt : std::optional<scene::Mesh>(mesh));
    if (mesh.material < scene.materials.size()) {
      const scene::Material& m = scene.materials[mesh.material];
      if (m.base_color_texture && has_uv) b.base_slot = slot_for(*m.base_color_texture, true);
      if (m.normal_texture && has_uv && has_tangents)
        b.normal_slot = slot_for(*m.normal_texture, false);
      if ((m.base_color_texture || m.normal_texture) && !has_uv)
        warnings_.push_back("mesh '" + mesh.name + "' has no uv0: its textures are ignored");
      else if (m.normal_texture && !has_tangents)
        warnings_.push_back("mesh '" + mesh.name + "' has no tangents: its normal map is ignored");
    }
    meshes_.push_back(std::move(b));
  }
}

namespace {

// A device-local buffer holding `data`, uploaded through a staging copy.
template <class T>
vk::Buffer device_buffer(const vk::Context& context, std::span<const T> data,
                         VkBufferUsageFlags usage, const std::string& name) {
  vk::Buffer buffer(context, {data.size() * sizeof(T), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              vk::MemoryUsage::DeviceLocal, name});
  vk::upload_buffer(context, buffer, data);
  return buffer;
}

// The atlas gutter's triangles (scene/UvAtlas.h): copies of their host vertices at the
// gutter's UVs, with the host's island and the gutter's depth.
std::vector<GpuVertex> gutter_vertices(const scene::Mesh::AtlasGutter& g,
                                       const std::vector<GpuVertex>& vertices,
                                       const scene::UvIslands& islands) {
  std::vector<GpuVertex> gutter;
  gutter.reserve(g.vertices.size());
  for (std::size_t k = 0; k < g.vertices.size(); ++k) {
    GpuVertex v = vertices.at(g.vertices[k]);
    const float island = float(islands.vertex_island.at(g.host.at(k / 3)));
    v.atlas[0] = g.uv[k].x;
    v.atlas[1] = g.uv[k].y;
    v.atlas[2] = island;
    v.atlas[3] = g.depth[k];
    gutter.push_back(v);
  }
  return gutter;
}

}  // namespace

GpuScene::MeshBuffers GpuScene::upload_geometry(const vk::Context& context, const scene::Mesh& mesh,
                                                bool scatters) {
  const bool has_uv = mesh.uv0.size() == mesh.positions.size();
  const bool has_tangents = mesh.tangents.size() == mesh.positions.size();
  const std::vector<glm::vec2>& atlas = scene::sss_uvs(mesh);
  // The SSS UVs of every mesh that has usable ones, scattering or not: a material can be
  // given subsurface scattering on a live renderer (set_materials). Inert until it is.
  const bool sss_uvs = atlas.size() == mesh.positions.size() &&
                       (!mesh.uv_atlas.empty() || scene::check_uvs(mesh).usable);
  const scene::UvIslands islands =
      sss_uvs ? scene::uv_islands(atlas, mesh.indices) : scene::UvIslands{};
  if (scatters && islands.count > 2048)  // the atlases store island + 1 in half floats (exact to 2048)
    warnings_.push_back("mesh '" + mesh.name + "' has " + std::to_string(islands.count) +
                        " UV islands: texture-space SSS tells apart 2048, so islands 2048 "
                        "apart may blur into each other where they are within a kernel");
  // Every mesh, scattering or not, for the same reason; the bake costs a BVH build and a
  // ray per vertex.
  const std::vector<float> thickness = reference::inward_thickness(mesh);
  std::vector<GpuVertex> vertices(mesh.positions.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    const glm::vec3& n = mesh.normals[i];
    GpuVertex& v = vertices[i];
    v = {{p.x, p.y, p.z}, {n.x, n.y, n.z}, {0.0f, 0.0f}, {0.0f, 0.0f, 0.0f, 0.0f}, {},
         i < thickness.size() ? thickness[i] : -1.0f};
    if (sss_uvs)
      for (int c = 0; c < 4; ++c)
        v.atlas[c] = c < 2 ? atlas[i][c] : c == 2 ? float(islands.vertex_island[i]) : 0.0f;
    if (has_uv) {
      v.uv[0] = mesh.uv0[i].x;
      v.uv[1] = mesh.uv0[i].y;
    }
    if (has_tangents)
      for (int c = 0; c < 4; ++c) v.tangent[c] = mesh.tangents[i][c];
  }
  MeshBuffers b;
  b.sss_uvs = sss_uvs;
  b.name = mesh.name;
  b.bounds = mesh.bounds;
  b.index_count = static_cast<std::uint32_t>(mesh.indices.size());
  b.material = mesh.material;
  if (!vertices.empty() && !mesh.indices.empty()) {
    b.vertices = device_buffer(context, std::span<const GpuVertex>(vertices),
                               VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, mesh.name + " vertices");
    b.indices = device_buffer(context, std::span<const std::uint32_t>(mesh.indices),
                              VK_BUFFER_USAGE_INDEX_BUFFER_BIT, mesh.name + " indices");
  }
  const scene::Mesh::AtlasGutter& g = mesh.uv_atlas_gutter;
  if (sss_uvs && !mesh.uv_atlas.empty() && !g.vertices.empty()) {
    const std::vector<GpuVertex> gutter = gutter_vertices(g, vertices, islands);
    b.gutter = device_buffer(context, std::span<const GpuVertex>(gutter),
                             VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, mesh.name + " gutter");
    b.gutter_vertices = static_cast<std::uint32_t>(gutter.size());
    b.gutter_hosts = g.vertices;
  }
  return b;
}

void GpuScene::set_materials(const std::vector<scene::Material>& materials) {
  if (materials.size() != materials_.size())
    throw std::invalid_argument("the scene has " + std::to_string(materials_.size()) +
                                " materials, not " + std::to_string(materials.size()));
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].base_color_texture != materials_[i].base_color_texture ||
        materials[i].normal_texture != materials_[i].normal_texture)
      throw std::invalid_argument("material '" + materials[i].name +
                                  "': textures cannot change on a live renderer");
  materials_ = materials;
}

void GpuScene::ensure_sss_uvs(const vk::Context& context, const std::vector<scene::Material>& materials) {
  bool waited = false;
  for (std::size_t i = 0; i < meshes_.size(); ++i) {
    if (!deferred_[i]) continue;
    const std::uint32_t m = meshes_[i].material;
    if (m >= materials.size() || !materials[m].sss.enabled) continue;
    // An atlas sized for the material's reach (scene::ensure_sss_atlases), on a scene of
    // this mesh alone.
    scene::Scene one;
    one.mm_per_unit = mm_per_unit_;
    one.materials = materials;
    one.meshes.push_back(*deferred_[i]);
    scene::ensure_sss_atlases(one, scene::kLoadAtlasOptions);
    MeshBuffers b = upload_geometry(context, one.meshes[0], true);
    if (!b.sss_uvs) {  // no atlas could be made: drawn without spread, and not tried again
      deferred_[i].reset();
      continue;
    }
    atlas_notes_.insert(atlas_notes_.end(), one.texture_notes.begin(), one.texture_notes.end());
    if (!waited) context.wait_idle();  // a frame in flight may still read the old buffers
    waited = true;
    b.base_slot = meshes_[i].base_slot;
    b.normal_slot = meshes_[i].normal_slot;
    meshes_[i] = std::move(b);
    deferred_[i].reset();
    // The atlas may have split vertices at its seams: the sky's transfers no longer match.
    geometry_.meshes[i].positions = one.meshes[0].positions;
    geometry_.meshes[i].normals = one.meshes[0].normals;
    geometry_.meshes[i].indices = one.meshes[0].indices;
    sky_.clear();
    sky_baked_ = false;
  }
}

double GpuScene::ensure_sky_occlusion(const vk::Context& context) {
  if (sky_baked_) return 0.0;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::vector<reference::SkyTransfer>> transfers = reference::sky_occlusion(geometry_);
  std::vector<SkyBuffers> sky(instances_.size());
  for (std::size_t i = 0; i < instances_.size(); ++i) {
    const MeshBuffers& mesh = meshes_[instances_[i].mesh];
    if (!mesh.vertices) continue;
    // A mesh without a whole triangle still draws its indices: zeros, so that binding 1
    // never keeps the previous instance's (shorter) buffer.
    const std::vector<reference::SkyTransfer> zeros(
        transfers[i].empty() ? geometry_.meshes[instances_[i].mesh].positions.size() : 0);
    const std::vector<reference::SkyTransfer>& t = transfers[i].empty() ? zeros : transfers[i];
    const std::string& name = instances_[i].node;
    sky[i].vertices = device_buffer(context, std::span<const reference::SkyTransfer>(t),
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, name + " sky transfer");
    if (mesh.gutter_vertices > 0) {
      std::vector<reference::SkyTransfer> gutter;
      gutter.reserve(mesh.gutter_vertices);
      for (const std::uint32_t v : mesh.gutter_hosts) gutter.push_back(t.at(v));
      sky[i].gutter = device_buffer(context, std::span<const reference::SkyTransfer>(gutter),
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, name + " gutter sky transfer");
    }
  }
  sky_ = std::move(sky);
  sky_baked_ = true;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

VkBuffer GpuScene::sky_buffer(std::size_t instance, bool gutter) const {
  if (!sky_baked_ || instance >= sky_.size()) return VK_NULL_HANDLE;
  const vk::Buffer& b = gutter ? sky_[instance].gutter : sky_[instance].vertices;
  return b ? b.handle() : VK_NULL_HANDLE;
}

std::vector<VkDescriptorImageInfo> GpuScene::texture_descriptors() const {
  std::vector<VkDescriptorImageInfo> out;
  for (std::uint32_t i = 0; i < shader::kMaxTextures; ++i) {
    const Slot& s = slots_[i < slots_.size() ? i : 0];
    out.push_back(s.image.descriptor(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, s.sampler.get()));
  }
  return out;
}

void GpuScene::push_constants(VkCommandBuffer cmd, VkPipelineLayout layout, const scene::Instance& instance,
                    int light_index, int object) const {
  const MeshBuffers& mesh = meshes_[instance.mesh];
  const scene::Material& material = materials_[mesh.material];
  shader::DrawPush push;
  push.model = to_shader(instance.world);
  push.material = {float(mesh.material), float(light_index), 0.0f, float(object)};
  push.base_color = {material.base_color.r, material.base_color.g, material.base_color.b,
                     material.base_color.a};
  push.textures = {float(mesh.base_slot), float(mesh.normal_slot), material.normal_scale, 0.0f};
  vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                     sizeof(push), &push);
}

void GpuScene::push_and_draw(VkCommandBuffer cmd, VkPipelineLayout layout, std::size_t instance,
                             int light_index, int object) const {
  const scene::Instance& i = instances_.at(instance);
  const MeshBuffers& mesh = meshes_[i.mesh];
  if (mesh.index_count == 0) return;
  push_constants(cmd, layout, i, light_index, object);
  const VkBuffer buffers[] = {mesh.vertices.handle(), sky_buffer(instance, false)};
  const VkDeviceSize offsets[] = {0, 0};
  vkCmdBindVertexBuffers(cmd, 0, buffers[1] ? 2 : 1, buffers, offsets);
  vkCmdBindIndexBuffer(cmd, mesh.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(cmd, mesh.index_count, 1, 0, 0, 0);
}

void GpuScene::draw(VkCommandBuffer cmd, VkPipelineLayout layout, int light_index) const {
  for (std::size_t i = 0; i < instances_.size(); ++i) push_and_draw(cmd, layout, i, light_index, -1);
}

void GpuScene::draw_instance(VkCommandBuffer cmd, VkPipelineLayout layout, std::size_t instance,
                             int object) const {
  push_and_draw(cmd, layout, instance, -1, object);
}

void GpuScene::draw_gutter(VkCommandBuffer cmd, VkPipelineLayout layout, std::size_t instance,
                           int object) const {
  const scene::Instance& i = instances_.at(instance);
  const MeshBuffers& mesh = meshes_[i.mesh];
  if (mesh.gutter_vertices == 0) return;
  push_constants(cmd, layout, i, -1, object);
  const VkBuffer buffers[] = {mesh.gutter.handle(), sky_buffer(instance, true)};
  const VkDeviceSize offsets[] = {0, 0};
  vkCmdBindVertexBuffers(cmd, 0, buffers[1] ? 2 : 1, buffers, offsets);
  vkCmdDraw(cmd, mesh.gutter_vertices, 1, 0, 0);
}

}  // namespace sss::renderer
