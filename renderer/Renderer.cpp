#include "renderer/Renderer.h"

#include "renderer/AntialiasPass.h"
#include "renderer/CameraSetup.h"
#include "renderer/CompositePass.h"
#include "renderer/DebugViewPass.h"
#include "renderer/GBufferPass.h"
#include "renderer/LightingPass.h"
#include "renderer/ShadowPass.h"
#include "renderer/SssGaussiansPass.h"
#include "renderer/SssSeparablePass.h"
#include "renderer/SssTexturePass.h"
#include "renderer/TextureGatherPass.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Sampler.h"
#include "renderer/vk/Transfer.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <stdexcept>

namespace sss::renderer {

namespace {

// Each side of a render target is at most 16384 (the CLI's cap) and at most the
// device's maxImageDimension2D, so that a size the device cannot make is refused before
// anything is created or replaced.
std::uint32_t max_side(const vk::Context& context) {
  return std::min<std::uint32_t>(16384, context.info().limits.maxImageDimension2D);
}

void check_size(const vk::Context& context, std::uint32_t width, std::uint32_t height) {
  const std::uint32_t max = max_side(context);
  if (width == 0 || height == 0 || width > max || height > max)
    throw std::invalid_argument("image size " + std::to_string(width) + "x" +
                                std::to_string(height) + " must be 1.." + std::to_string(max) +
                                " on each side (maxImageDimension2D of " +
                                context.info().name + ": " +
                                std::to_string(context.info().limits.maxImageDimension2D) + ")");
}

void check_options(const vk::Context& context, const RenderOptions& o) {
  check_size(context, o.width, o.height);
  if (o.shadow_map_size == 0 || o.shadow_map_size > max_side(context))
    throw std::invalid_argument("shadow map size must be 1.." + std::to_string(max_side(context)));
  const auto check_texture = [](std::uint32_t size, const std::string& what) {
    if (const std::string e = texture_size_error(size); !e.empty())
      throw std::invalid_argument(what + ": " + e);
  };
  check_texture(o.texture_size, "texture size");
  for (const TextureObjectOptions& t : o.texture_objects)
    check_texture(t.size, "texture size of object '" + t.name + "'");
  if (const std::string e = debug_range_error(o.debug_view, o.debug_range); !e.empty())
    throw std::invalid_argument("debug range: " + e);
  if (o.background)
    if (const std::string e = background_error(*o.background); !e.empty())
      throw std::invalid_argument("background: " + e);
}

const scene::Scene& checked(const vk::Context& context, const scene::Scene& scene,
                            const RenderOptions& o) {
  if (scene.cameras.empty()) throw std::invalid_argument("the scene has no camera");
  check_options(context, o);
  return scene;
}

std::uint32_t shadow_layers_for(const LightSetup& lights) {
  return std::max<std::uint32_t>(1, lights.count);
}

Samplers make_samplers(const vk::Context& context) {
  Samplers s;
  vk::SamplerDesc nearest(VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST);
  nearest.name = "nearest";
  s.nearest = vk::create_sampler(context, nearest);
  vk::SamplerDesc linear(VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST);
  linear.name = "linear";
  s.linear = vk::create_sampler(context, linear);
  vk::SamplerDesc shadow(VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST);
  shadow.compare = true;
  shadow.compare_op = VK_COMPARE_OP_LESS_OR_EQUAL;
  shadow.name = "shadow";
  s.shadow = vk::create_sampler(context, shadow);
  return s;
}

}  // namespace

Renderer::Renderer(const vk::Context& context, const scene::Scene& scene,
                   const RenderOptions& options)
    : context_(context),
      options_(options),
      camera_(checked(context, scene, options).cameras.front()),
      scene_lights_(scene.lights),
      bounds_(scene.bounds()),
      mm_per_unit_(scene.mm_per_unit),
      lights_(make_light_setup(scene_lights_, bounds_, options.shadow_map_size)),
      materials_(context, scene, options.separable_taps, options.single_scattering),
      scene_(context, scene),
      targets_(context, options.width, options.height, shadow_layers_for(lights_),
               options.shadow_map_size, FrameTargets::use_for(options, scene.environment.has_value())),
      frame_uniforms_(context, {sizeof(shader::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                vk::MemoryUsage::Dynamic, "frame uniforms"}),
      light_buffer_(context, {sizeof(shader::LightBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                              vk::MemoryUsage::Dynamic, "lights"}),
      samplers_(make_samplers(context)),
      environment_maps_(context),
      resources_{context, targets_, frame_uniforms_, light_buffer_,
                 materials_.buffer(), samplers_, scene_, environment_maps_, rect_},
      pool_(vk::create_command_pool(context, 0)),  // one command buffer: reset the pool
      fence_(vk::create_fence(context)),
      timer_(context) {
  store_environment(scene.environment);
  shadow_ = std::make_unique<ShadowPass>(resources_, lights_.shadowed);
  gbuffer_ = std::make_unique<GBufferPass>(resources_);
  lighting_ = std::make_unique<LightingPass>(resources_);
  update_sss_pass();
  composite_ = std::make_unique<CompositePass>(resources_);
  write_lights(lights_);
  write_frame_uniforms();
  cmd_ = vk::allocate_command_buffer(context, pool_.get());
}

Renderer::~Renderer() { context_.wait_idle(); }

void Renderer::write_frame_uniforms() {
  const CameraSetup camera = make_camera_setup(camera_, options_.width, options_.height);
  shader::FrameUniforms uniforms =
      make_frame_uniforms(camera, options_.width, options_.height, mm_per_unit_,
                          options_.exposure, lights_.count, options_.technique);
  uniforms.options.z = surface_key_stride(camera, bounds_, mm_per_unit_);
  uniforms.options.w = options_.transmission ? 1.0f : 0.0f;
  uniforms.flags.x = options_.fresnel ? 1.0f : 0.0f;
  uniforms.flags.y = options_.single_scattering ? 1.0f : 0.0f;
  uniforms.flags.z = !has_environment_ ? 0.0f : sky_on_ ? 2.0f : 1.0f;
  uniforms.flags.w = has_environment_ && options_.background_environment ? 1.0f : 0.0f;
  if (composite_) composite_->set_full_frame(uniforms.flags.w > 0.5f);
  rect_ = geometry_rect(camera, bounds_, options_.width, options_.height);
  uniforms.rect = {float(rect_.x0), float(rect_.y0), float(rect_.x1), float(rect_.y1)};
  frame_uniforms_.write(&uniforms, sizeof(uniforms));
}

void Renderer::write_lights(LightSetup lights) {
  lights_ = std::move(lights);
  for (std::size_t k = 0; k < environment_sh_.size(); ++k) lights_.block.environment[k] = environment_sh_[k];
  light_buffer_.write(&lights_.block, sizeof(lights_.block));
  shadow_->set_shadowed(lights_.shadowed);
  if (texture_) texture_->invalidate();
  collect_warnings();
}

void Renderer::collect_warnings() {
  warnings_ = lights_.warnings;
  warnings_.insert(warnings_.end(), scene_.warnings().begin(), scene_.warnings().end());
  if (texture_)
    warnings_.insert(warnings_.end(), texture_->warnings().begin(), texture_->warnings().end());
}

void Renderer::recreate_targets(std::uint32_t width, std::uint32_t height,
                                std::uint32_t shadow_layers, std::uint32_t shadow_size,
                                const FrameTargets::Use& use) {
  context_.wait_idle();  // a window may still be blitting the display image
  FrameTargets fresh(context_, width, height, shadow_layers, shadow_size, use);
  {
    // Destroyed member by member in reverse order: the shadow layer views before their image.
    const FrameTargets old = std::move(targets_);
  }
  targets_ = std::move(fresh);
  lighting_->write_descriptors();
  if (separable_) separable_->write_descriptors();
  if (gaussians_) gaussians_->write_descriptors();
  composite_->write_descriptors();
  if (debug_) debug_->write_descriptors();
  if (antialias_) antialias_->write_descriptors();
  if (texture_) texture_->write_descriptors();  // the shadow maps
}

void Renderer::update_sss_pass() {
  const int gaussians = materials_.data().max_gaussians;
  if (options_.technique != SssTechnique::Separable)
    separable_.reset();
  else if (!separable_)
    separable_ = std::make_unique<SssSeparablePass>(resources_);
  if (!(options_.technique == SssTechnique::Gaussians && gaussians > 0))
    gaussians_.reset();
  else if (!gaussians_)
    gaussians_ = std::make_unique<SssGaussiansPass>(resources_, gaussians);
  else
    gaussians_->set_gaussians(gaussians);
  // Texture space reads the SSS UVs: a scattering mesh without usable ones gets its atlas
  // now, the first time this mode (or its material's subsurface) is on.
  if (options_.technique == SssTechnique::Texture) scene_.ensure_sss_uvs(context_, scene_.materials());
  if (options_.technique != SssTechnique::Texture) {
    gather_.reset();
    texture_.reset();
  } else if (!texture_) {
    texture_ = std::make_unique<SssTexturePass>(resources_, options_);
    gather_ = std::make_unique<TextureGatherPass>(resources_);
  } else {
    texture_->configure(options_);
  }
  if (gather_) gather_->set_objects(*texture_);
  collect_warnings();
  update_display_passes();
}

void Renderer::update_display_passes() {
  const DebugView view = options_.debug_view;
  if (view == DebugView::None) {
    debug_.reset();
  } else {
    if (!debug_) debug_ = std::make_unique<DebugViewPass>(resources_);
  }
  // FXAA, never under a debug view (its colour bar maps values to colours): the rule that
  // also gives the pass its source target (FrameTargets::use_for), always options_'s here.
  if (!targets_.use.display_source)
    antialias_.reset();
  else if (!antialias_)
    antialias_ = std::make_unique<AntialiasPass>(resources_);
  gbuffer_->set_uv_stretch(targets_.use.uv_stretch);
  if (separable_) separable_->set_write_scattered(view == DebugView::Scattered);
  update_sky();
}

void Renderer::update_sky() {
  // On only once every part is in place: a bake or a pipeline build that throws leaves the
  // frame unoccluded (flags.z 1), never reading a sky target that nothing drew, nor
  // drawing a sky pipeline without its vertex binding.
  sky_on_ = false;
  const bool sky = targets_.use.sky_blocked;
  try {
    if (sky) {
      const double seconds = scene_.ensure_sky_occlusion(context_);
      if (seconds > 0.0) sky_bake_seconds_ = seconds;
    }
    gbuffer_->set_sky(sky);
    if (texture_) texture_->set_sky(sky);
  } catch (...) {
    gbuffer_->set_sky(false);
    if (texture_) texture_->set_sky(false);
    if (composite_) write_frame_uniforms();  // flags.z 1 (in the constructor: written later)
    throw;
  }
  sky_on_ = sky;
}

std::array<float, 2> Renderer::debug_range() const {
  const DebugView view = options_.debug_view;
  if (!debug_view_has_range(view)) return {0.0f, 0.0f};
  if (options_.debug_range != std::array<float, 2>{0.0f, 0.0f}) return options_.debug_range;
  // The objects the view is about: those drawn with an SSS material (all, if none).
  const std::vector<scene::Instance>& instances = scene_.instances();
  const std::vector<scene::Material>& materials = scene_.materials();
  std::vector<std::size_t> chosen;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const std::uint32_t m = scene_.mesh_material(instances[i].mesh);
    if (m < materials.size() && materials[m].sss.enabled) chosen.push_back(i);
  }
  if (view == DebugView::KernelRadius) {
    // 1 px (below it the view is magenta) to the largest radius a pixel can show: the
    // kernel's reach times the camera plane's pixels per mm at the object's nearest depth
    // (sss.glsl's pixels_per_mm; foreshortening only shortens it). The default 1..64 px
    // saturated on the bunny, whose skin reaches past 64 px at 960x540.
    constexpr std::array<float, 2> kFallback{1.0f, 64.0f};  // the camera inside an object
    const glm::mat4 proj = scene::clip_from_view(camera_, options_.width, options_.height);
    const double focal_px = 0.5 * std::min(double(options_.width) * double(proj[0][0]),
                                           double(options_.height) * std::abs(double(proj[1][1])));
    const glm::mat4 view_from_world = camera_.view();
    const MaterialData& data = materials_.data();
    double top = 0.0;
    for (std::size_t i : chosen) {
      const std::uint32_t m = scene_.mesh_material(instances[i].mesh);
      if (m >= data.profiles.size() || !data.profiles[m]) continue;  // does not scatter
      double mm_per_px_plane = mm_per_unit_;  // orthographic: one depth for all
      if (camera_.projection == scene::Projection::Perspective) {
        // The nearest depth: view space looks down -z, so the box's largest z.
        const double z_min = -double(scene_.instance_bounds(i).transformed(view_from_world).max.z);
        if (!(z_min > 0.0)) return kFallback;
        mm_per_px_plane = z_min * mm_per_unit_;
      }
      // The width in float, as the shaders see it.
      const double range_mm = static_cast<float>(data.profiles[m]->kernel.range_mm);
      top = std::max(top, range_mm * focal_px / mm_per_px_plane);
    }
    return {1.0f, float(std::max(2.0, top))};
  }
  // Thickness, uv stretch: up to the largest object's bounding diameter (a chord is no
  // longer), and pi times it for uv stretch (a UV sphere's u spans its circumference). The
  // scene's diameter, the old top, made a 30 mm sphere in a larger scene one dark colour.
  if (chosen.empty())
    for (std::size_t i = 0; i < instances.size(); ++i) chosen.push_back(i);
  double diameter = 0.0;
  for (std::size_t i : chosen) {
    const scene::Bounds b = scene_.instance_bounds(i);
    if (!b.empty()) diameter = std::max(diameter, 2.0 * double(b.radius()) * mm_per_unit_);
  }
  if (!(diameter > 0.0)) diameter = 1.0;
  return {0.0f, float(view == DebugView::UvStretch ? std::numbers::pi * diameter : diameter)};
}

void Renderer::set_camera(const scene::Camera& camera) {
  camera_ = camera;
  write_frame_uniforms();
}

void Renderer::store_environment(const std::optional<scene::Environment>& environment) {
  has_environment_ = environment.has_value();
  for (std::size_t k = 0; k < environment_sh_.size(); ++k) {
    const glm::vec3 c = environment ? environment->irradiance_sh[k] : glm::vec3(0.0f);
    environment_sh_[k] = {c.x, c.y, c.z, 0.0f};
  }
  context_.wait_idle();  // a frame may still read the levels
  environment_maps_.upload(environment);
  if (composite_) composite_->write_descriptors();  // the background image may be new
}

void Renderer::set_environment(const std::optional<scene::Environment>& environment) {
  store_environment(environment);
  const FrameTargets::Use use = FrameTargets::use_for(options_, has_environment_);
  if (use != targets_.use)
    recreate_targets(options_.width, options_.height,
                     static_cast<std::uint32_t>(targets_.shadow_layers.size()),
                     options_.shadow_map_size, use);
  update_sky();
  write_lights(lights_);
  write_frame_uniforms();
}

void Renderer::set_lights(const std::vector<scene::Light>& lights) {
  LightSetup setup = make_light_setup(lights, bounds_, options_.shadow_map_size);
  const std::uint32_t layers = shadow_layers_for(setup);
  if (layers > targets_.shadow_layers.size())
    recreate_targets(options_.width, options_.height, layers, options_.shadow_map_size, targets_.use);
  scene_lights_ = lights;
  write_lights(std::move(setup));
  write_frame_uniforms();  // the light count
}

void Renderer::set_materials(const std::vector<scene::Material>& materials) {
  set_materials(materials, build_material_data(materials, options_.separable_taps,
                                               options_.single_scattering));
}

void Renderer::set_materials(const std::vector<scene::Material>& materials, MaterialData data) {
  if (data.separable_taps != options_.separable_taps)
    throw std::invalid_argument("set_materials: kernels built for " +
                                std::to_string(data.separable_taps) + " taps, the renderer uses " +
                                std::to_string(options_.separable_taps));
  if (data.single_scattering != options_.single_scattering)
    throw std::invalid_argument(std::string("set_materials: profiles built ") +
                                (data.single_scattering ? "without" : "with") +
                                " their single scattering, the renderer adds S(1) " +
                                (options_.single_scattering ? "apart" : "not at all"));
  if (data.profiles.size() != materials.size())
    throw std::invalid_argument("set_materials: material data for " +
                                std::to_string(data.profiles.size()) + " materials, got " +
                                std::to_string(materials.size()));
  scene_.set_materials(materials);  // checks the count and the textures first
  materials_.replace(context_, std::move(data));
  update_sss_pass();
  if (texture_) texture_->invalidate();
}

void Renderer::set_options(const RenderOptions& options) {
  check_options(context_, options);
  std::optional<MaterialData> data;
  if (options.separable_taps != options_.separable_taps ||
      options.single_scattering != options_.single_scattering)
    data = build_material_data(scene_.materials(), options.separable_taps,
                               options.single_scattering);  // checks taps
  const bool size_changed = options.width != options_.width || options.height != options_.height;
  const bool shadow_changed = options.shadow_map_size != options_.shadow_map_size;
  // Another technique or view may read targets this one made 1 x 1, or no longer read some.
  const FrameTargets::Use use = FrameTargets::use_for(options, has_environment_);
  if (size_changed || shadow_changed || use != targets_.use)
    recreate_targets(options.width, options.height,
                     static_cast<std::uint32_t>(targets_.shadow_layers.size()),
                     options.shadow_map_size, use);
  if (data) materials_.replace(context_, std::move(*data));
  // These change the texture path's irradiance atlases (entry Fresnel is in E), and a
  // refit its blurred ones (the Gaussians, and E's transmitted part divided by the total).
  const bool transmission_changed = options.transmission != options_.transmission ||
                                    options.fresnel != options_.fresnel || data.has_value();
  options_ = options;
  if (shadow_changed)
    write_lights(make_light_setup(scene_lights_, bounds_, options_.shadow_map_size));
  update_sss_pass();
  if (texture_ && (transmission_changed || shadow_changed)) texture_->invalidate();
  write_frame_uniforms();
}

void Renderer::resize(std::uint32_t width, std::uint32_t height) {
  check_size(context_, width, height);
  if (width == options_.width && height == options_.height) return;
  RenderOptions options = options_;
  options.width = width;
  options.height = height;
  set_options(options);
}

graph::FrameGraph Renderer::build_graph() {
  graph::FrameGraph graph;
  // The screen passes write only rect_: the rest of the output is background (zero, or
  // the display's opaque background colour, given as sRGB codes).
  graph.add_pass("clear", false).step(
      {{&targets_.hdr, graph::use::kClear}, {&targets_.display, graph::use::kClear}},
      [this](VkCommandBuffer cmd) {
        const VkClearColorValue zero{};
        VkClearColorValue background{};
        if (const auto& c = options_.background) background = {{(*c)[0], (*c)[1], (*c)[2], 1.0f}};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, targets_.hdr.handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
        vkCmdClearColorImage(cmd, targets_.display.handle(), VK_IMAGE_LAYOUT_GENERAL, &background,
                             1, &all);
      });
  shadow_->add_to(graph, options_.transmission || options_.debug_view == DebugView::Thickness);
  if (texture_) texture_->add_to(graph, materials_.data());
  gbuffer_->add_to(graph);
  if (gather_) gather_->add_to(graph);
  lighting_->add_to(graph);
  if (separable_) separable_->add_to(graph);
  if (gaussians_) gaussians_->add_to(graph);
  composite_->add_to(graph);
  if (antialias_) antialias_->add_to(graph);
  if (debug_) {
    debug_->set_view(options_.debug_view, debug_range());  // follows the camera and the fits
    debug_->add_to(graph);
  }
  // Read back (read_hdr, read_display, read_specular) and blitted by the window in GENERAL.
  for (const vk::Image* image : {&targets_.hdr, &targets_.display, &targets_.specular})
    graph.keep(*image, display_layout());
  return graph;
}

std::string Renderer::describe_frame() { return build_graph().describe(); }
std::string Renderer::frame_pass_order() { return build_graph().pass_order(); }

void Renderer::record(VkCommandBuffer cmd) {
  timer_.reset(cmd);
  build_graph().record(cmd, timer_);
}

void Renderer::render_frame() {
  const auto start = std::chrono::steady_clock::now();
  // The pool holds cmd_ only; resetting the pool is the cheap way (best practices:
  // vkCreateCommandPool-command-buffer-reset).
  VK_CHECK(vkResetCommandPool(context_.device(), pool_.get(), 0));
  VkFence fence = fence_.get();
  VK_CHECK(vkResetFences(context_.device(), 1, &fence));
  vk::record_and_submit(context_, cmd_, fence, [this](VkCommandBuffer cmd) { record(cmd); });
  vk::wait_for_fence(context_, fence, std::chrono::seconds(600));
  const auto end = std::chrono::steady_clock::now();
  stats_.passes = timer_.resolve();
  stats_.gpu_ms = 0.0;
  for (const vk::PassTime& p : stats_.passes) stats_.gpu_ms += p.ms;
  stats_.cpu_ms = std::chrono::duration<double, std::milli>(end - start).count();
  rendered_ = true;
}

image::Image Renderer::read(const vk::Image& image) const {
  if (!rendered_) throw std::logic_error("Renderer: no frame rendered yet");
  const std::vector<std::byte> bytes = vk::download_image(context_, image, VK_IMAGE_LAYOUT_GENERAL);
  image::Image out(static_cast<int>(image.width()), static_cast<int>(image.height()));
  switch (image.format()) {
    case VK_FORMAT_R8G8B8A8_UNORM:
      for (std::size_t i = 0; i < out.rgba.size(); ++i)
        out.rgba[i] = float(std::to_integer<unsigned>(bytes[i])) / 255.0f;
      break;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      for (std::size_t i = 0; i < out.rgba.size(); ++i) {
        std::uint16_t h;
        std::memcpy(&h, bytes.data() + 2 * i, sizeof h);
        out.rgba[i] = glm::unpackHalf1x16(h);
      }
      break;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      std::memcpy(out.rgba.data(), bytes.data(), out.rgba.size() * sizeof(float));
      break;
    default:
      throw std::logic_error("Renderer::read: unexpected format of " + image.desc().name);
  }
  return out;
}

image::Image Renderer::read_atlas(std::size_t object, Atlas which) const {
  if (!texture_ || object >= texture_->objects().size())
    throw std::out_of_range("Renderer::read_atlas: no texture-space object " +
                            std::to_string(object));
  if (!texture_->computed(object))
    throw std::logic_error("Renderer::read_atlas: object " + texture_->objects()[object].options.name +
                           " has not been computed since its textures were made");
  return read(which == Atlas::Scattered    ? texture_->scattered(object)
              : which == Atlas::Irradiance ? texture_->irradiance(object)
                                           : texture_->stretch(object));
}

image::Image Renderer::read_hdr() const { return read(targets_.hdr); }
image::Image Renderer::read_display() const {
  image::Image display = read(targets_.display);
  image::unpremultiply(display);  // only anti-aliased silhouettes have 0 < alpha < 1
  return display;
}
image::Image Renderer::read_specular() const { return read(targets_.specular); }

}  // namespace sss::renderer
