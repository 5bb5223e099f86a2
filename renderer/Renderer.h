// Renderer: the real-time frame of DESIGN.md §5 for one scene. It owns the targets, the
// buffers and one object per pass, and orders them:
//
//   shadow -> gbuffer -> lighting -> [sss separable | sss gaussians] -> composite
//   shadow -> sss texture -> gbuffer -> sss texture gather -> lighting -> composite
//     (--sss texture: the objects' atlases are updated before the G-buffer, and the
//     lookup draw fills `accum`, which the composite reads)
//   ... -> composite -> [antialias (RenderOptions::antialias) | debug view]
//
// Headless and windowed use are the same Renderer (the window only presents `display`).
// render_frame() records one command buffer, submits it and waits for its fence, so
// one frame is in flight; GPU times per pass (GpuTimer, named after the pass) and the CPU
// frame time are in stats().
//
// Live changes (the viewer): set_camera / set_lights / set_materials / set_options /
// resize change what the next render_frame() draws; the frame then equals the one a
// Renderer constructed with the changed input would draw. Call them between frames (never
// while another thread renders). set_camera and a set_lights that needs no more shadow
// layers only write host-visible uniforms; set_materials refits the profiles (CPU) and
// re-uploads the material buffer; a new size, shadow map size or more shadow layers waits
// for the device to be idle and recreates the targets. A call that throws
// std::invalid_argument changes nothing.
#pragma once

#include "renderer/FrameResources.h"
#include "renderer/FrameTargets.h"
#include "renderer/GpuScene.h"
#include "renderer/LightSetup.h"
#include "renderer/MaterialTable.h"
#include "renderer/RenderOptions.h"
#include "renderer/graph/FrameGraph.h"
#include "image/Image.h"
#include "scene/Scene.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/GpuTimer.h"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sss::vk {
class Context;
}

namespace sss::renderer {

class ShadowPass;
class GBufferPass;
class LightingPass;
class SssSeparablePass;
class SssGaussiansPass;
class CompositePass;
class AntialiasPass;
class DebugViewPass;
class SssTexturePass;
class TextureGatherPass;

struct FrameStats {
  std::vector<vk::PassTime> passes;  // GPU ms per pass, in frame order
  double gpu_ms = 0.0;               // sum of the passes
  double cpu_ms = 0.0;               // record + submit + wait, wall clock
};

class Renderer {
 public:
  // Throws std::invalid_argument for an unusable scene or options (no camera, zero size,
  // too many materials), VulkanError for device failures.
  Renderer(const vk::Context& context, const scene::Scene& scene, const RenderOptions& options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  void render_frame();

  // The view for the next frame (the scene's cameras are not kept; cameras[0] was the
  // first view). Cheap: new frame uniforms, no GPU allocation.
  void set_camera(const scene::Camera& camera);
  // New lights (LightSetup: block, shadow matrices); grows the shadow-map array if it
  // holds fewer layers than the lights need (warnings() follows).
  void set_lights(const std::vector<scene::Light>& lights);
  // A new environment light (none: nullopt): the light block, the frame uniforms and an
  // upload of its prefiltered levels (0.8 MB; waits for the device).
  void set_environment(const std::optional<scene::Environment>& environment);
  // New materials, as many as the scene's and with the same textures (else
  // std::invalid_argument): refits the Gaussians and separable kernels (build_material_data),
  // re-uploads the table into the same buffer, updates the draw constants.
  void set_materials(const std::vector<scene::Material>& materials);
  // The same with the fits already built (build_material_data(materials, taps) on any
  // thread): only the upload runs here. std::invalid_argument (nothing changes) when
  // `data` was built for another tap count than options().separable_taps or another
  // material count.
  void set_materials(const std::vector<scene::Material>& materials, MaterialData data);
  // Technique / taps / exposure / views; a new size, shadow map size, or a technique or
  // view that reads other targets (FrameTargets::Use) recreates the targets.
  // Invalid options (as for the constructor) throw std::invalid_argument.
  void set_options(const RenderOptions& options);
  // Recreates the frame targets at width x height; 0 (a minimized window) or more than
  // 16384 on a side throws std::invalid_argument.
  void resize(std::uint32_t width, std::uint32_t height);

  // The tonemapped rgba8 target (sRGB-encoded by hand, kDisplayFormat, TRANSFER_SRC usage)
  // for a window to blit. After render_frame() it is in display_layout() (GENERAL), last
  // written by compute-shader storage writes (src: COMPUTE_SHADER / SHADER_STORAGE_WRITE);
  // leave it in that layout. Recreated by resize(): take the reference again afterwards.
  const vk::Image& display_image() const { return targets_.display; }
  static constexpr VkImageLayout display_layout() { return VK_IMAGE_LAYOUT_GENERAL; }
  // The frame's passes, in order, with the images each step reads and writes
  // (graph::FrameGraph::describe; docs/ARCHITECTURE.md's frame table).
  std::string describe_frame();
  // The same passes' names only, "clear -> shadow -> ..." (renderer/README.md).
  std::string frame_pass_order();
  const FrameStats& stats() const { return stats_; }
  // The device memory of the frame's targets (FrameTargets: the technique's and the view's
  // images, the shadow maps), without the scene's buffers and the texture path's atlases.
  VkDeviceSize target_bytes() const { return targets_.memory_bytes(); }

  // The last frame: linear radiance L (rgb; alpha 1 on geometry, 0 on background) and
  // the display image (tonemapped, sRGB-encoded, codes / 255; straight alpha, which is 0
  // or 1 except at anti-aliased silhouettes, where it is the coverage).
  image::Image read_hdr() const;
  image::Image read_display() const;
  // The last frame's specular radiance towards the eye (rgb, linear), the part of read_hdr()
  // that does not scatter: the error budget takes it apart from the scattered light. Only
  // pixels with geometry (read_hdr()'s alpha > 0.5) hold a value; the target is not cleared
  // behind the background.
  image::Image read_specular() const;

  const MaterialData& materials() const { return materials_.data(); }
  // The texture path (--sss texture), or null in the other modes: its objects and their
  // update counts.
  const SssTexturePass* texture_pass() const { return texture_.get(); }
  // One texture-space object's atlas after the last frame (rgba, linear; alpha the UV
  // island + 1, 0 on empty texels): its scattered irradiance Σ w_i (E * G_i), its dilated
  // irradiance E, or its stretch map (mm per texel along u, v).
  enum class Atlas { Scattered, Irradiance, Stretch };
  image::Image read_atlas(std::size_t object, Atlas which) const;
  const std::vector<std::string>& warnings() const { return warnings_; }
  // The UV atlases texture space generated so far ("mesh NAME: generated a UV atlas (...)").
  const std::vector<std::string>& atlas_notes() const { return scene_.atlas_notes(); }
  const RenderOptions& options() const { return options_; }
  // The debug view's heat-map range for the next frame, in the view's unit: the options'
  // debug_range when set, else the view's own: kernel-radius 1 px to the largest radius
  // any SSS pixel can have from this camera; thickness 0 to the largest SSS object's
  // bounding diameter in mm (every object's if none scatters); uv-stretch 0 to pi x that.
  // {0, 0} for a view without a heat map.
  std::array<float, 2> debug_range() const;
  const scene::Camera& camera() const { return camera_; }
  // The wall time of the last sky-occlusion bake (RenderOptions::sky_occlusion), 0 if none ran.
  double sky_bake_seconds() const { return sky_bake_seconds_; }

 private:
  // The frame as passes that declare their images; record() records it.
  graph::FrameGraph build_graph();
  void record(VkCommandBuffer cmd);
  // rgba8 (codes / 255), rgba16f or rgba32f images read back as float RGBA.
  image::Image read(const vk::Image& image) const;
  void write_frame_uniforms();
  void write_lights(LightSetup lights);
  // Waits for the device to be idle, replaces targets_ and points the passes' descriptor
  // sets at the new images.
  void recreate_targets(std::uint32_t width, std::uint32_t height, std::uint32_t shadow_layers,
                        std::uint32_t shadow_size, const FrameTargets::Use& use);
  // separable_ / gaussians_ for options_ and the material table.
  void update_sss_pass();
  // debug_ and what the view needs from the other passes, for options_.debug_view, and
  // antialias_ (options_.antialias, never under a debug view).
  void update_display_passes();
  // With FrameTargets::Use::sky_blocked: bakes the scene's sky occlusion if it is not
  // (GpuScene::ensure_sky_occlusion) and switches the G-buffer and the texture path to
  // their sky variants; otherwise back to the plain ones.
  void update_sky();
  // warnings_: the lights', the scene's and the texture path's.
  void collect_warnings();
  // has_environment_, environment_sh_ and environment_maps_ from the scene's environment.
  void store_environment(const std::optional<scene::Environment>& environment);

  const vk::Context& context_;
  RenderOptions options_;
  scene::Camera camera_;
  std::vector<scene::Light> scene_lights_;
  // The scene's environment light as LightBlock::environment holds it (all 0 without one).
  bool has_environment_ = false;
  double sky_bake_seconds_ = 0.0;
  bool sky_on_ = false;  // the G-buffer and the texture path draw the sky target (update_sky)
  std::array<shader::vec4, 9> environment_sh_{};
  scene::Bounds bounds_;  // of the scene's instances (shadow fits)
  double mm_per_unit_;
  std::vector<std::string> warnings_;
  LightSetup lights_;
  MaterialTable materials_;
  GpuScene scene_;
  FrameTargets targets_;
  vk::Buffer frame_uniforms_;
  vk::Buffer light_buffer_;
  Samplers samplers_;
  EnvironmentMaps environment_maps_;
  PixelRect rect_;  // geometry_rect of the current camera and size (write_frame_uniforms)
  FrameResources resources_;
  std::unique_ptr<ShadowPass> shadow_;
  std::unique_ptr<GBufferPass> gbuffer_;
  std::unique_ptr<LightingPass> lighting_;
  std::unique_ptr<SssSeparablePass> separable_;
  std::unique_ptr<SssGaussiansPass> gaussians_;
  std::unique_ptr<CompositePass> composite_;
  std::unique_ptr<DebugViewPass> debug_;  // only while options_.debug_view != None
  std::unique_ptr<AntialiasPass> antialias_;  // only with Antialias::Fxaa and no debug view
  std::unique_ptr<SssTexturePass> texture_;     // only in SssTechnique::Texture
  std::unique_ptr<TextureGatherPass> gather_;   // with texture_
  vk::CommandPoolHandle pool_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  vk::FenceHandle fence_;
  vk::GpuTimer timer_;
  FrameStats stats_;
  bool rendered_ = false;
};

}  // namespace sss::renderer
