// SssTexturePass ("sss texture"): texture-space diffusion (d'Eon & Luebke 2007, GPU Gems 3
// ch. 14; DESIGN.md §5). Every instance whose material scatters and whose mesh has usable
// SSS UVs (GpuScene::has_sss_uvs) is an object with its own atlas textures, at its
// TextureObjectOptions::size. Updating an object:
//   1. raster: its triangles drawn at their atlas UVs (texture_irradiance.*): an atlas
//      G-buffer (world position, UV island, normal, base colour) and the stretch map (mm
//      per texel along u and v);
//   2. lighting (texture_lighting.comp): irradiance E per texel with the frame's lights,
//      shadow maps and transmission (shared/shading.glsl, as the screen path);
//   3. dilation (texture_dilate.comp): empty texels near an island take its border's
//      values, so nothing black is blurred or looked up along seams;
//   4. blur (sss_texture.comp): the fit's Gaussians incrementally (v_i - v_{i-1}), each
//      separable in u then v, scaled per texel by the stretch map, accumulating
//      Σ w_i (E * G_i) into the object's `scattered` texture.
// TextureGatherPass looks `scattered` up at each pixel. An object updates in the frame
// after it is created or invalidated, and in every frame when its update policy is
// TextureUpdate::EveryFrame; otherwise its textures keep the last result.
#pragma once

#include "renderer/Program.h"
#include "renderer/FrameResources.h"
#include "renderer/RenderOptions.h"
#include "renderer/graph/FrameGraph.h"
#include "renderer/vk/Image.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sss::renderer {

struct MaterialData;

class SssTexturePass {
 public:
  static constexpr const char* kName = "sss texture";

  struct Object {
    std::size_t instance = 0;
    std::uint32_t material = 0;
    TextureObjectOptions options;  // name = the instance's name
    std::uint64_t updates = 0;     // frames in which it was recomputed
  };

  SssTexturePass(const FrameResources& resources, const RenderOptions& options);
  ~SssTexturePass();
  SssTexturePass(const SssTexturePass&) = delete;
  SssTexturePass& operator=(const SssTexturePass&) = delete;
  // The objects for the scene's current materials and `options`: new objects and objects
  // whose size changed get fresh textures (and update next frame); the others keep theirs.
  void configure(const RenderOptions& options);
  // Lights, materials, transmission or shadow maps changed: every object updates next frame.
  void invalidate();
  // With an environment and the scene's sky occlusion baked (as GBufferPass::set_sky):
  // the atlas raster also writes the sky's blocked irradiance, into each object's temp
  // texture, where texture_lighting.comp reads it before it writes E there. A change
  // invalidates every object.
  void set_sky(bool on);
  // Points the lighting sets at the current shadow maps (after FrameTargets were recreated).
  void write_descriptors();
  // Updates the objects that need it; `materials` gives each one's Gaussian count.
  void add_to(graph::FrameGraph& graph, const MaterialData& materials);

  const std::vector<Object>& objects() const { return objects_; }
  // Whether object i's textures hold a result (it was updated since they were made).
  bool computed(std::size_t object) const;
  // Object i's scattered irradiance Σ w_i (E * G_i) (rgba16f, GENERAL, alpha the island + 1
  // on the island and on its seam gutter, -(island + 1) on dilated texels, 0 on empty
  // ones), and its other textures for tests and debugging.
  const vk::Image& scattered(std::size_t object) const;
  const vk::Image& irradiance(std::size_t object) const;  // dilated E, alpha island + 1
  const vk::Image& stretch(std::size_t object) const;     // dilated mm per texel along u, v
  // Instances that scatter but are left out (no usable UVs, more than
  // SSS_MAX_TEXTURE_OBJECTS): they are shaded without spread.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  struct Textures;
  void update(VkCommandBuffer cmd, Textures& t, const Object& object, int gaussians);
  void write_lighting(Textures& t);  // t's lighting set: the frame's buffers and shadow maps
  // configure's stages: the scattering instances with usable UVs, within the object limit
  // (the others, and --texture-object names that match none, go to warnings); then every
  // object's descriptor sets, from fresh pools.
  std::vector<Object> select_objects(const RenderOptions& options, std::vector<std::string>& warnings) const;
  void allocate_object_sets();

  const FrameResources& r_;
  Program raster_;  // the irradiance raster into the atlas (graphics)
  vk::PipelineHandle sky_raster_;  // its sky variant, on raster_'s layout (set_sky)
  bool sky_ = false;
  VkDescriptorSet raster_set_ = VK_NULL_HANDLE;
  Program lighting_;
  Program dilate_;
  Program blur_;
  std::vector<Object> objects_;
  std::vector<Textures> textures_;  // one per object
  vk::Image depth_;  // the atlas raster's depth (own triangles before the gutter), largest size
  std::vector<std::string> warnings_;
};

}  // namespace sss::renderer
