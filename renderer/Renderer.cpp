#include "renderer/Renderer.h"

#include "renderer/CameraSetup.h"
#include "renderer/CompositePass.h"
#include "renderer/GBufferPass.h"
#include "renderer/LightingPass.h"
#include "renderer/ShadowPass.h"
#include "renderer/SssGaussiansPass.h"
#include "renderer/SssSeparablePass.h"
#include "renderer/vk/Barrier.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Sampler.h"
#include "renderer/vk/Transfer.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace sss::renderer {

namespace {

const scene::Scene& checked(const scene::Scene& scene, const RenderOptions& o) {
  if (scene.cameras.empty()) throw std::invalid_argument("the scene has no camera");
  if (o.width == 0 || o.height == 0 || o.width > 16384 || o.height > 16384)
    throw std::invalid_argument("image size must be 1..16384 on each side");
  if (o.shadow_map_size == 0 || o.shadow_map_size > 16384)
    throw std::invalid_argument("shadow map size must be 1..16384");
  return scene;
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

int sss_mode_index(const RenderOptions& o) {
  if (o.sss == SssMode::Off) return 0;
  return o.kind == SssKind::Separable ? 1 : 2;
}

}  // namespace

Renderer::Renderer(const vk::Context& context, const scene::Scene& scene,
                   const RenderOptions& options)
    : context_(context),
      options_(options),
      lights_(make_light_setup(checked(scene, options), options.shadow_map_size)),
      materials_(context, scene, options.separable_taps),
      scene_(context, scene),
      targets_(context, options.width, options.height,
               std::max<std::uint32_t>(1, lights_.count), options.shadow_map_size),
      frame_uniforms_(context, {sizeof(shader::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                vk::MemoryUsage::Dynamic, "frame uniforms"}),
      light_buffer_(context, {sizeof(shader::LightBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                              vk::MemoryUsage::Dynamic, "lights"}),
      samplers_(make_samplers(context)),
      resources_{context, targets_, frame_uniforms_, light_buffer_,
                 materials_.buffer(), samplers_, scene_},
      pool_(vk::create_command_pool(context, VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT)),
      fence_(vk::create_fence(context)),
      timer_(context) {
  warnings_ = lights_.warnings;
  warnings_.insert(warnings_.end(), scene_.warnings().begin(), scene_.warnings().end());
  const CameraSetup camera = make_camera_setup(scene.cameras.front(), options.width, options.height);
  const shader::FrameUniforms uniforms =
      make_frame_uniforms(camera, options.width, options.height, scene.mm_per_unit,
                          options.exposure, lights_.count, sss_mode_index(options));
  frame_uniforms_.write(&uniforms, sizeof(uniforms));
  light_buffer_.write(&lights_.block, sizeof(lights_.block));

  shadow_ = std::make_unique<ShadowPass>(resources_, lights_.shadowed);
  gbuffer_ = std::make_unique<GBufferPass>(resources_);
  lighting_ = std::make_unique<LightingPass>(resources_);
  if (options.sss == SssMode::Screen && options.kind == SssKind::Separable)
    separable_ = std::make_unique<SssSeparablePass>(resources_);
  if (options.sss == SssMode::Screen && options.kind == SssKind::Gaussians &&
      materials_.data().max_gaussians > 0)
    gaussians_ = std::make_unique<SssGaussiansPass>(resources_, materials_.data().max_gaussians);
  composite_ = std::make_unique<CompositePass>(resources_);
  cmd_ = vk::allocate_command_buffer(context, pool_.get());
}

Renderer::~Renderer() { context_.wait_idle(); }

void Renderer::record(VkCommandBuffer cmd) {
  timer_.reset(cmd);
  // Every target from UNDEFINED (last frame's contents are not needed) to its first
  // layout, after everything the previous frame did with it.
  const vk::Scope before{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT};
  const vk::Scope depth_access{
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
  const vk::Scope color_access{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
  const vk::Scope compute_access{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT |
                                     VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  std::vector<VkImageMemoryBarrier2> barriers = {
      vk::image_barrier(targets_.shadow, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, before, depth_access),
      vk::image_barrier(targets_.depth, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, before, depth_access),
      vk::image_barrier(targets_.normal, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, before, color_access),
      vk::image_barrier(targets_.albedo, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, before, color_access)};
  for (const vk::Image* image : targets_.compute_targets())
    barriers.push_back(vk::image_barrier(*image, VK_IMAGE_LAYOUT_UNDEFINED,
                                         VK_IMAGE_LAYOUT_GENERAL, before, compute_access));
  vk::pipeline_barrier(cmd, barriers);

  shadow_->record(cmd, timer_);
  gbuffer_->record(cmd, timer_);
  lighting_->record(cmd, timer_);
  if (separable_) separable_->record(cmd, timer_);
  if (gaussians_) gaussians_->record(cmd, timer_);
  composite_->record(cmd, timer_);
}

void Renderer::render_frame() {
  const auto start = std::chrono::steady_clock::now();
  VK_CHECK(vkResetCommandBuffer(cmd_, 0));
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

image::Image Renderer::read(const vk::Image& image, bool eight_bit) const {
  if (!rendered_) throw std::logic_error("Renderer: no frame rendered yet");
  const std::vector<std::byte> bytes = vk::download_image(context_, image, VK_IMAGE_LAYOUT_GENERAL);
  image::Image out(static_cast<int>(image.width()), static_cast<int>(image.height()));
  if (eight_bit) {
    for (std::size_t i = 0; i < out.rgba.size(); ++i)
      out.rgba[i] = float(std::to_integer<unsigned>(bytes[i])) / 255.0f;
  } else {
    std::memcpy(out.rgba.data(), bytes.data(), out.rgba.size() * sizeof(float));
  }
  return out;
}

image::Image Renderer::read_hdr() const { return read(targets_.hdr, false); }
image::Image Renderer::read_display() const { return read(targets_.display, true); }

}  // namespace sss::renderer
