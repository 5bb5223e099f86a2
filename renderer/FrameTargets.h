// FrameTargets: every image one frame writes, at the output size, with the formats of
// DESIGN.md §5. Layouts: the G-buffer and the shadow maps are attachments while drawn
// and SHADER_READ_ONLY_OPTIMAL afterwards; every compute target stays in GENERAL (read
// through samplers or storage loads, written as storage images). The frame graph
// (renderer/graph) moves each image from UNDEFINED to its first use's layout at the start
// of the frame and derives every barrier after that from the passes' declarations.
#pragma once

#include "renderer/RenderOptions.h"
#include "renderer/vk/Handle.h"
#include "renderer/vk/Image.h"

#include <cstdint>
#include <vector>

namespace sss::vk {
class Context;
}

namespace sss::renderer {

inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
// The G-buffer depth after the G-buffer pass: sampled by compute passes and tested (not
// written) by the texture path's lookup draw.
inline constexpr VkImageLayout kDepthReadLayout = VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
inline constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // xyz normal, w inward thickness mm
inline constexpr VkFormat kAlbedoFormat = VK_FORMAT_R8G8B8A8_UNORM;       // rgb albedo, a id
inline constexpr VkFormat kUvStretchFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // mm per u, v; has UVs
inline constexpr VkFormat kSkyBlockedFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // rgb blocked sky E
inline constexpr VkFormat kLightingFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
// Irradiance and the separable pass's horizontal result: rgb value, alpha the surface key
// (depth mm + id x stride, sss.glsl), which needs float32.
inline constexpr VkFormat kKeyedFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kHdrFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;  // sRGB-encoded by hand

struct FrameTargets {
  // The targets that only some techniques and views read. A frame that does not read one
  // gets it 1 x 1: its descriptors stay valid, and no shader reads it in that frame (the
  // shaders test the technique or the view before they fetch). `sss-viewer --headless
  // --stats` prints the total; README "Frame memory" lists it per technique.
  struct Use {
    bool gaussian_blur = true;   // blur_temp, blur_b: gaussians
    bool scattered = true;       // blur_a: gaussians, and separable's scattered view
    bool accum = true;           // gaussians, texture (its lookup's colour attachment)
    bool line = true;            // sss_line, sss_prefix: separable
    bool uv_stretch = true;      // the uv-stretch view (the G-buffer's third attachment)
    // sky_blocked: an environment with RenderOptions::sky_occlusion, outside the uv-stretch
    // view (the G-buffer's third attachment, gbuffer_sky.frag)
    bool sky_blocked = true;
    bool display_source = true;  // FXAA
    bool operator==(const Use&) const = default;
  };
  // What a frame with these options reads; `environment`: the scene has an environment light.
  static Use use_for(const RenderOptions& options, bool environment);

  FrameTargets(const vk::Context& context, std::uint32_t width, std::uint32_t height,
               std::uint32_t shadow_layers, std::uint32_t shadow_size, const Use& use);

  std::uint32_t width, height;
  Use use;
  vk::Image shadow;  // D32 array, one layer per light
  std::vector<vk::ImageViewHandle> shadow_layers;
  // The same depths without the shadow pass's slope-scaled bias, for thickness
  // (shared/thickness.glsl: transmission, the thickness view). D32 array like shadow.
  vk::Image light_depth;
  std::vector<vk::ImageViewHandle> light_depth_layers;
  vk::Image depth, normal, albedo;          // G-buffer
  // uv-stretch debug view only: drawn by the G-buffer's second pipeline; like normal and
  // albedo, a colour attachment then SHADER_READ_ONLY_OPTIMAL in every frame.
  vk::Image uv_stretch;
  // The environment's irradiance that the scene blocks (rgb; gbuffer_sky.frag, read by
  // lighting.comp): a colour attachment then SHADER_READ_ONLY_OPTIMAL, like normal.
  vk::Image sky_blocked;
  vk::Image irradiance, specular;           // lighting (irradiance: kKeyedFormat)
  vk::Image surface;  // lighting, for SSS: view depth in mm, material id (rgba32f)
  // SSS gaussians; accum is also the texture path's lookup target (a colour attachment in
  // GENERAL, TextureGatherPass).
  vk::Image blur_temp, blur_a, blur_b, accum;
  vk::Image sss_line;  // SSS separable: the horizontal pass's result (kKeyedFormat)
  // SSS separable: running sums of the pass's input along its lines, rgb the value's sum
  // over the run so far, alpha the run's first pixel (sss_prefix.comp; rgba32f).
  vk::Image sss_prefix;
  vk::Image hdr, display;                   // composite
  // The display image as composite left it, read by the anti-aliasing pass (a copy, so
  // no pixel reads a neighbour the pass already wrote). Not a compute target: the pass
  // takes it from UNDEFINED to TRANSFER_DST_OPTIMAL to SHADER_READ_ONLY_OPTIMAL.
  vk::Image display_source;

  // The compute targets (GENERAL layout).
  std::vector<const vk::Image*> compute_targets() const;
  // The device memory of every target, shadow maps included.
  VkDeviceSize memory_bytes() const;
};

}  // namespace sss::renderer
