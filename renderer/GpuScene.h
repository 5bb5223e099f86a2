// GpuScene: the scene's meshes in device-local vertex and index buffers, its material
// textures (base colour as sRGB, normal maps as linear RGBA8, one sampler each, no mips
// yet), and the draw of every instance with its DrawPush (model matrix, material index,
// roughness, colour, texture slots). The G-buffer and the shadow maps draw the same list.
#pragma once

#include "scene/Scene.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Handle.h"
#include "renderer/vk/Image.h"

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sss::vk {
class Context;
class GraphicsPipelineBuilder;
}

namespace sss::renderer {

struct GpuVertex {
  float position[3];
  float normal[3];
  float uv[2];
  float tangent[4];  // xyz, w handedness; zero when the mesh has none
  // The texture path's atlas (scene::sss_uvs): u, v, the vertex's UV island
  // (scene::uv_islands), and the atlas raster's depth: 0 for the mesh's own triangles,
  // 0.25..0.75 for its seam gutter's (Mesh::uv_atlas_gutter), so that its own win. All
  // zero when the mesh's SSS UVs are not usable.
  float atlas[4];
  // Inward thickness (reference::inward_thickness): the distance from the vertex along -n
  // out of the mesh, in mesh units; -1 without a hit. The G-buffer turns it into world mm
  // for the environment's transmission.
  float thickness;
};

// Every GpuVertex attribute (locations 0..5) from binding 0: what the pipelines drawing
// the scene's meshes with all attributes declare (G-buffer, texture path).
void add_vertex_input(vk::GraphicsPipelineBuilder& builder);
// The sky's blocked transfer (reference::SkyTransfer, 9 floats) as locations 6..8 from
// binding 1, which GpuScene binds per instance once ensure_sky_occlusion has baked it: the
// sky variants of the G-buffer and of the texture path's atlas raster declare it.
void add_sky_vertex_input(vk::GraphicsPipelineBuilder& builder);

class GpuScene {
 public:
  GpuScene(const vk::Context& context, const scene::Scene& scene);

  // Binds the vertex/index buffers and draws each instance; push constants go to
  // `layout` (vertex and fragment stages). light_index is written into DrawPush for the
  // shadow pass (ignored elsewhere).
  void draw(VkCommandBuffer cmd, VkPipelineLayout layout, int light_index = -1) const;
  // One instance (scene.instances order); DrawPush::material.w = `object` (the texture
  // path's object index).
  void draw_instance(VkCommandBuffer cmd, VkPipelineLayout layout, std::size_t instance,
                     int object) const;
  // The instance's seam gutter triangles (non-indexed), for the texture path's atlas raster;
  // nothing when its mesh has none.
  void draw_gutter(VkCommandBuffer cmd, VkPipelineLayout layout, std::size_t instance,
                   int object) const;

  const std::vector<scene::Instance>& instances() const { return instances_; }
  // Instance i's box in world units (its mesh's bounds, transformed).
  scene::Bounds instance_bounds(std::size_t i) const {
    return meshes_[instances_[i].mesh].bounds.transformed(instances_[i].world);
  }
  std::uint32_t mesh_material(std::uint32_t mesh) const { return meshes_[mesh].material; }
  const std::string& mesh_name(std::uint32_t mesh) const { return meshes_[mesh].name; }
  // Whether the mesh's SSS UVs (scene::sss_uvs) can hold an irradiance texture: a
  // generated atlas, or a uv0 that passes scene::check_uvs. Checked at construction for
  // every mesh; a mesh without either gets an atlas when ensure_sss_uvs finds its
  // material scattering (the renderer asks in texture mode only).
  bool has_sss_uvs(std::uint32_t mesh) const { return meshes_[mesh].sss_uvs; }

  // SSS_MAX_TEXTURES descriptors (SHADER_READ_ONLY_OPTIMAL); unused slots hold a white
  // 1x1 texture.
  std::vector<VkDescriptorImageInfo> texture_descriptors() const;
  const std::vector<std::string>& warnings() const { return warnings_; }
  // "mesh NAME: generated a UV atlas (...)" for each atlas ensure_sss_uvs built, in order.
  const std::vector<std::string>& atlas_notes() const { return atlas_notes_; }

  // The material constants the draws push (colour, roughness, normal scale) come from
  // `materials` from now on. Same count and the same textures as the scene's (the texture
  // slots are not rebuilt): otherwise std::invalid_argument and nothing changes.
  void set_materials(const std::vector<scene::Material>& materials);
  const std::vector<scene::Material>& materials() const { return materials_; }
  // For each mesh without SSS UVs whose material scatters in `materials`: builds its UV
  // atlas (scene::ensure_sss_atlases, sized for the material's reach) and uploads its
  // vertices again with it (waiting for the device first), adding a note to
  // atlas_notes(). Only texture-space SSS reads the atlas, so the renderer calls this
  // when that mode is on; the screen path and the CPU reference never pay for it. The
  // atlas build runs on the calling thread (its cost: renderer/README.md, "Costs").
  void ensure_sss_uvs(const vk::Context& context, const std::vector<scene::Material>& materials);
  // Bakes the sky occlusion of every instance (reference::sky_occlusion, on the calling
  // thread with TBB) and uploads it, unless it is baked already; ensure_sss_uvs drops it
  // when it rebuilds a mesh (its vertices may be split). From then on every draw binds
  // each instance's transfers at binding 1. Returns the bake's wall time in seconds (0
  // when nothing was baked). Keeps geometry_ (a copy of the meshes' positions, normals and
  // indices) for it from construction, as an environment can be switched on later.
  double ensure_sky_occlusion(const vk::Context& context);
  bool has_sky_occlusion() const { return sky_baked_; }

 private:
  struct MeshBuffers {
    vk::Buffer vertices;
    vk::Buffer indices;
    std::uint32_t index_count = 0;
    std::uint32_t material = 0;
    int base_slot = -1;    // texture slots usable by this mesh (it has uv0 / tangents)
    int normal_slot = -1;
    bool sss_uvs = false;  // has_sss_uvs
    vk::Buffer gutter;     // GpuVertex x 3 per gutter triangle
    std::uint32_t gutter_vertices = 0;
    std::vector<std::uint32_t> gutter_hosts;  // per gutter vertex: the mesh vertex it copies
    std::string name;
    scene::Bounds bounds;  // the mesh's, local
  };
  // The mesh's vertex, index and gutter buffers and its SSS UVs (no texture slots).
  MeshBuffers upload_geometry(const vk::Context& context, const scene::Mesh& mesh, bool scatters);
  void push_constants(VkCommandBuffer cmd, VkPipelineLayout layout, const scene::Instance& instance,
                      int light_index, int object) const;
  void push_and_draw(VkCommandBuffer cmd, VkPipelineLayout layout, std::size_t instance,
                     int light_index, int object) const;
  struct Slot {
    vk::Image image;
    vk::SamplerHandle sampler;
  };
  int add_texture(const vk::Context& context, const scene::Scene& scene, std::uint32_t texture,
                  bool srgb);

  // Per instance: its mesh's vertices' sky transfers, and its gutter's (copies of the
  // host vertices', as gutter_vertices copies the vertices).
  struct SkyBuffers {
    vk::Buffer vertices, gutter;
  };
  std::vector<SkyBuffers> sky_;
  bool sky_baked_ = false;
  // What the sky bake casts rays against: every mesh's positions, normals and indices as
  // drawn (ensure_sss_uvs keeps them current), the instances, mm_per_unit.
  scene::Scene geometry_;
  // The buffer that binding 1 reads for `instance` (gutter: its gutter's), or null.
  VkBuffer sky_buffer(std::size_t instance, bool gutter) const;

  std::vector<MeshBuffers> meshes_;
  std::vector<scene::Instance> instances_;
  std::vector<scene::Material> materials_;
  std::vector<std::optional<scene::Mesh>> deferred_;  // per mesh: kept for ensure_sss_uvs
  double mm_per_unit_ = 1000.0;
  std::vector<Slot> slots_;  // slots_[0] is the white dummy
  std::vector<std::string> warnings_;
  std::vector<std::string> atlas_notes_;
};

}  // namespace sss::renderer
