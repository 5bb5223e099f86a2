#include "renderer/FrameTargets.h"

namespace sss::renderer {

namespace {

constexpr VkImageUsageFlags kComputeUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

vk::Image make(const vk::Context& c, std::uint32_t w, std::uint32_t h, VkFormat f,
               VkImageUsageFlags usage, const char* name) {
  return vk::Image(c, {w, h, f, usage, name});
}

}  // namespace

FrameTargets::Use FrameTargets::use_for(const RenderOptions& o, bool environment) {
  const SssTechnique t = o.technique;
  Use use;
  use.gaussian_blur = t == SssTechnique::Gaussians;
  use.scattered = t == SssTechnique::Gaussians ||
                  (t == SssTechnique::Separable && o.debug_view == DebugView::Scattered);
  use.accum = t == SssTechnique::Gaussians || t == SssTechnique::Texture;
  use.line = t == SssTechnique::Separable;
  use.uv_stretch = o.debug_view == DebugView::UvStretch;
  use.sky_blocked = environment && o.sky_occlusion && !use.uv_stretch;
  // FXAA, never under a debug view (Renderer::update_display_passes follows this).
  use.display_source = o.antialias == Antialias::Fxaa && o.debug_view == DebugView::None;
  return use;
}

FrameTargets::FrameTargets(const vk::Context& context, std::uint32_t w, std::uint32_t h,
                           std::uint32_t layers, std::uint32_t shadow_size, const Use& used)
    : width(w), height(h), use(used) {
  vk::ImageDesc shadow_desc(shadow_size, shadow_size, kDepthFormat,
                            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                VK_IMAGE_USAGE_SAMPLED_BIT,
                            "shadow maps");
  shadow_desc.array_layers = layers;
  shadow_desc.view_type = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  shadow = vk::Image(context, shadow_desc);
  for (std::uint32_t i = 0; i < layers; ++i) shadow_layers.push_back(shadow.create_view(i));
  shadow_desc.name = "light depth";
  light_depth = vk::Image(context, shadow_desc);
  for (std::uint32_t i = 0; i < layers; ++i) light_depth_layers.push_back(light_depth.create_view(i));

  const VkImageUsageFlags attachment = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  depth = make(context, w, h, kDepthFormat,
               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
               "gbuffer depth");
  normal = make(context, w, h, kNormalFormat, attachment, "gbuffer normal");
  albedo = make(context, w, h, kAlbedoFormat, attachment, "gbuffer albedo");
  // A target this frame does not read: 1 x 1 (Use).
  const auto side = [](bool read, std::uint32_t n) { return read ? n : 1u; };
  uv_stretch = make(context, side(use.uv_stretch, w), side(use.uv_stretch, h), kUvStretchFormat,
                    attachment, "gbuffer uv stretch");
  sky_blocked = make(context, side(use.sky_blocked, w), side(use.sky_blocked, h), kSkyBlockedFormat,
                     attachment, "gbuffer sky blocked");
  irradiance = make(context, w, h, kKeyedFormat, kComputeUsage, "irradiance");
  specular = make(context, w, h, kLightingFormat, kComputeUsage, "specular");
  surface = make(context, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, kComputeUsage, "surface");
  const std::uint32_t gw = side(use.gaussian_blur, w), gh = side(use.gaussian_blur, h);
  blur_temp = make(context, gw, gh, kLightingFormat, kComputeUsage, "sss temp");
  blur_a = make(context, side(use.scattered, w), side(use.scattered, h), kLightingFormat,
                kComputeUsage, "sss a");
  blur_b = make(context, gw, gh, kLightingFormat, kComputeUsage, "sss b");
  accum = make(context, side(use.accum, w), side(use.accum, h), kLightingFormat,
               kComputeUsage | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "sss accum");
  const std::uint32_t lw = side(use.line, w), lh = side(use.line, h);
  sss_line = make(context, lw, lh, kKeyedFormat, kComputeUsage, "sss line");
  sss_prefix = make(context, lw, lh, kKeyedFormat, kComputeUsage, "sss prefix");
  // Cleared each frame outside the screen passes' rect (Renderer::record).
  hdr = make(context, w, h, kHdrFormat, kComputeUsage | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "hdr");
  display = make(context, w, h, kDisplayFormat, kComputeUsage | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                 "display");
  display_source = make(context, side(use.display_source, w), side(use.display_source, h), kDisplayFormat,
                        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "display source");
}

VkDeviceSize FrameTargets::memory_bytes() const {
  VkDeviceSize total = shadow.memory_bytes() + light_depth.memory_bytes();
  for (const vk::Image* image : {&depth, &normal, &albedo, &uv_stretch, &sky_blocked, &display_source})
    total += image->memory_bytes();
  for (const vk::Image* image : compute_targets()) total += image->memory_bytes();
  return total;
}

std::vector<const vk::Image*> FrameTargets::compute_targets() const {
  return {&irradiance, &specular, &surface, &blur_temp, &blur_a, &blur_b, &accum, &sss_line, &sss_prefix,
          &hdr, &display};
}

}  // namespace sss::renderer
