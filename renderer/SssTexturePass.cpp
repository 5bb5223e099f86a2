#include "renderer/SssTexturePass.h"

#include "renderer/GBufferPass.h"
#include "renderer/GaussianPingPong.h"
#include "renderer/MaterialTable.h"
#include "renderer/vk/Barrier.h"
#include "renderer/vk/GraphicsPipeline.h"
#include "renderer/vk/Pipeline.h"
#include "renderer/vk/Rendering.h"
#include "shaders/shared/frame.h"
#include "shaders/sss_texture.comp.bindings.h"
#include "shaders/sss_texture.comp.h"
#include "shaders/texture_dilate.comp.bindings.h"
#include "shaders/texture_lighting.comp.bindings.h"
#include "shaders/texture_dilate.comp.h"
#include "shaders/texture_lighting.comp.h"
#include "shaders/texture_irradiance.frag.h"
#include "shaders/texture_irradiance.vert.h"
#include "shaders/texture_irradiance_sky.frag.h"
#include "shaders/texture_irradiance_sky.vert.h"

#include <algorithm>
#include <array>
#include <optional>
#include <cstddef>
#include <stdexcept>
#include <utility>

namespace sss::renderer {

namespace {

constexpr VkFormat kAtlasFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
namespace lit = shader::bindings::texture_lighting_comp;
namespace dil = shader::bindings::texture_dilate_comp;
namespace blur = shader::bindings::sss_texture_comp;

// sky: the variant that also writes the sky's blocked irradiance (a fifth target).
vk::PipelineHandle raster_pipeline(const vk::Context& context, VkPipelineLayout layout, bool sky) {
  vk::GraphicsPipelineBuilder builder;
  builder.vertex_shader(sky ? std::span<const uint32_t>(sss_spv_texture_irradiance_sky_vert)
                            : std::span<const uint32_t>(sss_spv_texture_irradiance_vert))
      .fragment_shader(sky ? std::span<const uint32_t>(sss_spv_texture_irradiance_sky_frag)
                           : std::span<const uint32_t>(sss_spv_texture_irradiance_frag))
      .color(VK_FORMAT_R32G32B32A32_SFLOAT)  // position
      .color(kAtlasFormat)                   // normal
      .color(kAtlasFormat)                   // albedo
      .color(kAtlasFormat);                  // stretch
  if (sky) builder.color(kAtlasFormat);      // the sky's blocked irradiance (temp)
  builder.depth(kDepthFormat, vk::DepthTest::Write)  // own triangles (z 0) win over the gutter
      .cull(VK_CULL_MODE_NONE);
  add_vertex_input(builder);
  if (sky) add_sky_vertex_input(builder);
  return builder.build(context, layout, sky ? "texture irradiance sky" : "texture irradiance");
}

// Whatever touched the atlases before (the previous frame's lookups, their creation).
constexpr vk::Scope kBefore{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                            VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};

}  // namespace

// One object's atlas textures, in GENERAL, rgba16f but for the position. The raster
// writes position, normal, a (albedo), b (raw stretch) and with an environment temp (the
// sky's blocked irradiance); the lighting writes temp (raw E); the dilation writes irradiance and stretch; then a and b are the blur's ping-pong
// pair and temp its intermediate.
struct SssTexturePass::Textures {
  std::uint32_t size = 0;
  vk::Image position, normal, a, b, irradiance, stretch, temp, scattered;
  bool initialized = false;  // moved out of UNDEFINED
  bool dirty = true;
  VkDescriptorSet lighting = VK_NULL_HANDLE, dilate = VK_NULL_HANDLE;
  GaussianPingPong blur;  // irradiance, then a / b via temp

  Textures(const vk::Context& context, std::uint32_t n, const std::string& name) : size(n) {
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const auto make = [&](const char* what, VkImageUsageFlags extra,
                          VkFormat format = kAtlasFormat) {
      return vk::Image(context, {n, n, format, usage | extra, name + " atlas " + what});
    };
    position = make("position", VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_FORMAT_R32G32B32A32_SFLOAT);
    normal = make("normal", VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    a = make("a", VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    b = make("b", VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    irradiance = make("irradiance", 0);
    stretch = make("stretch", 0);
    temp = make("temp", VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);  // the sky raster's fifth target
    scattered = make("scattered", 0);
  }
  std::array<const vk::Image*, 8> all() const {
    return {&position, &normal, &a, &b, &irradiance, &stretch, &temp, &scattered};
  }
};

SssTexturePass::SssTexturePass(const FrameResources& resources, const RenderOptions& options)
    : r_(resources),
      raster_(r_.context, surface_set_bindings(), sizeof(shader::DrawPush),
              VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 1, "texture irradiance",
              [&](VkPipelineLayout layout) { return raster_pipeline(r_.context, layout, false); }),
      lighting_(r_.context, lit::kAll, sss_spv_texture_lighting_comp,
                sizeof(shader::TexturePush), shader::kMaxTextureObjects, "texture lighting"),
      dilate_(r_.context, dil::kAll, sss_spv_texture_dilate_comp, 0,
              shader::kMaxTextureObjects, "texture dilate"),
      blur_(r_.context, blur::kAll, sss_spv_sss_texture_comp, sizeof(shader::TexturePush),
            5 * shader::kMaxTextureObjects, kName) {
  raster_set_ = raster_.allocate();
  write_descriptors();
  configure(options);
}

SssTexturePass::~SssTexturePass() = default;

void SssTexturePass::write_descriptors() {
  write_surface_set(raster_set_, r_);
  for (Textures& t : textures_) write_lighting(t);
}

void SssTexturePass::write_lighting(Textures& t) {
  const VkSampler nearest = r_.samplers.nearest.get();
  const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL;
  vk::DescriptorWriter(t.lighting)
      .uniform_buffer(lit::Frame, r_.frame_uniforms)
      .uniform_buffer(lit::Lights, r_.lights)
      .storage_buffer(lit::Materials, r_.materials)
      .combined_image(lit::position_tex, t.position, nearest, general)
      .combined_image(lit::normal_tex, t.normal, nearest, general)
      .combined_image(lit::albedo_tex, t.a, nearest, general)
      .combined_image(lit::shadow_tex, r_.targets.shadow, r_.samplers.shadow.get())
      .combined_image(lit::light_depth_tex, r_.targets.light_depth, nearest)
      .storage_image(lit::irradiance_img, t.temp)
      .update(r_.context);
}

std::vector<SssTexturePass::Object> SssTexturePass::select_objects(const RenderOptions& options,
                                                                   std::vector<std::string>& warnings) const {
  std::vector<Object> objects;
  const std::vector<scene::Instance>& instances = r_.scene.instances();
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const std::uint32_t mesh = instances[i].mesh;
    const std::uint32_t material = r_.scene.mesh_material(mesh);
    if (material >= r_.scene.materials().size() || !r_.scene.materials()[material].sss.enabled)
      continue;
    const std::string& name = instances[i].node;
    if (!r_.scene.has_sss_uvs(mesh)) {
      warnings.push_back("object " + name + " (mesh " + r_.scene.mesh_name(mesh) +
                         ") has no usable UVs for texture-space SSS: drawn without spread");
      continue;
    }
    if (objects.size() == shader::kMaxTextureObjects) {
      warnings.push_back("object " + name + ": more than " +
                         std::to_string(shader::kMaxTextureObjects) +
                         " objects in texture space; drawn without spread");
      continue;
    }
    objects.push_back({i, material, texture_options_for(options, name), 0});
  }
  for (const TextureObjectOptions& t : options.texture_objects)
    if (std::none_of(objects.begin(), objects.end(),
                     [&](const Object& o) { return o.options.name == t.name; }))
      warnings.push_back("texture object '" + t.name +
                         "' names no subsurface instance with usable UVs: ignored");
  return objects;
}

void SssTexturePass::allocate_object_sets() {
  lighting_.pool.reset();
  dilate_.pool.reset();
  blur_.pool.reset();
  const VkSampler nearest = r_.samplers.nearest.get();
  const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL;
  for (Textures& t : textures_) {
    t.lighting = lighting_.allocate();
    write_lighting(t);
    t.dilate = dilate_.allocate();
    vk::DescriptorWriter(t.dilate)
        .combined_image(dil::raw_irradiance_tex, t.temp, nearest, general)
        .combined_image(dil::raw_stretch_tex, t.b, nearest, general)
        .storage_image(dil::irradiance_img, t.irradiance)
        .storage_image(dil::stretch_img, t.stretch)
        .update(r_.context);
    t.blur.allocate(blur_);
    const auto write = [&](VkDescriptorSet set, const vk::Image& in, const vk::Image& out) {
      vk::DescriptorWriter(set)
          .storage_buffer(blur::Materials, r_.materials)
          .combined_image(blur::stretch_tex, t.stretch, nearest, general)
          .combined_image(blur::input_tex, in, nearest, general)
          .storage_image(blur::output_img, out)
          .storage_image(blur::accum_img, t.scattered)
          .update(r_.context);
    };
    t.blur.write(t.irradiance, t.a, t.b, t.temp, write);
  }
}

void SssTexturePass::configure(const RenderOptions& options) {
  std::vector<std::string> warnings;
  std::vector<Object> objects = select_objects(options, warnings);

  // Keep the textures of an object that stays at the same size; the GPU is idle between
  // frames (Renderer calls this between render_frame calls), so sets can be rewritten.
  // Everything that can throw (the new images) is made before anything changes, so a
  // failed allocation leaves the pass as it was.
  std::vector<std::size_t> kept(objects.size(), objects_.size());  // index into objects_
  std::vector<bool> taken(objects_.size(), false);
  std::vector<std::optional<Textures>> fresh(objects.size());
  std::uint32_t largest = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    Object& o = objects[i];
    largest = std::max(largest, o.options.size);
    for (std::size_t k = 0; k < objects_.size(); ++k)
      if (!taken[k] && objects_[k].instance == o.instance &&
          objects_[k].options.size == o.options.size) {
        kept[i] = k;
        taken[k] = true;
        o.updates = objects_[k].updates;
        break;
      }
    if (kept[i] == objects_.size()) fresh[i].emplace(r_.context, o.options.size, o.options.name);
  }
  vk::Image depth;
  if (largest > 0 && depth_.width() != largest)
    depth = vk::Image(r_.context, {largest, largest, kDepthFormat,
                                   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "atlas depth"});
  std::vector<Textures> textures;
  textures.reserve(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i)
    textures.push_back(fresh[i] ? std::move(*fresh[i]) : std::move(textures_[kept[i]]));
  objects_ = std::move(objects);
  textures_ = std::move(textures);
  warnings_ = std::move(warnings);
  if (depth) depth_ = std::move(depth);

  allocate_object_sets();
}

void SssTexturePass::set_sky(bool on) {
  if (on == sky_) return;
  if (on && !sky_raster_) sky_raster_ = raster_pipeline(r_.context, raster_.layout.get(), true);
  sky_ = on;
  invalidate();
}

void SssTexturePass::invalidate() {
  for (Textures& t : textures_) t.dirty = true;
}

bool SssTexturePass::computed(std::size_t object) const {
  return object < textures_.size() && textures_[object].initialized;
}

const vk::Image& SssTexturePass::scattered(std::size_t object) const {
  return textures_.at(object).scattered;
}
const vk::Image& SssTexturePass::irradiance(std::size_t object) const {
  return textures_.at(object).irradiance;
}
const vk::Image& SssTexturePass::stretch(std::size_t object) const {
  return textures_.at(object).stretch;
}

void SssTexturePass::update(VkCommandBuffer cmd, Textures& t, const Object& object, int count) {
  const vk::Scope general_access{
      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT |
          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  std::vector<VkImageMemoryBarrier2> barriers;
  for (const vk::Image* image : t.all())
    barriers.push_back(vk::image_barrier(*image,
                                         t.initialized ? VK_IMAGE_LAYOUT_GENERAL
                                                       : VK_IMAGE_LAYOUT_UNDEFINED,
                                         VK_IMAGE_LAYOUT_GENERAL, kBefore, general_access));
  barriers.push_back(vk::image_barrier(
      depth_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
      {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
       VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT},
      {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
       VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT}));
  vk::pipeline_barrier(cmd, barriers);
  t.initialized = true;

  // 1. Raster: the atlas G-buffer (position + island, normal, albedo), the stretch, and
  // with an environment the sky's blocked irradiance.
  std::array<vk::ColorTarget, 5> colors = {
      vk::ColorTarget(t.position.view()), vk::ColorTarget(t.normal.view()), vk::ColorTarget(t.a.view()),
      vk::ColorTarget(t.b.view()), vk::ColorTarget(t.temp.view())};
  for (vk::ColorTarget& c : colors) c.layout = VK_IMAGE_LAYOUT_GENERAL;
  const vk::DepthTarget depth(depth_.view());
  vk::begin_rendering(cmd, {t.size, t.size}, std::span<const vk::ColorTarget>(colors.data(), sky_ ? 5 : 4),
                      &depth);
  raster_.bind(cmd, sky_ ? sky_raster_.get() : raster_.pipeline.get(), raster_set_);
  r_.scene.draw_instance(cmd, raster_.layout.get(), object.instance, -1);
  r_.scene.draw_gutter(cmd, raster_.layout.get(), object.instance, -1);
  vk::end_rendering(cmd);
  const VkMemoryBarrier2 rastered = vk::memory_barrier(
      {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT},
      {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
           VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT});  // the lighting writes temp, which the sky raster wrote
  vk::pipeline_barrier(cmd, {}, {}, {&rastered, 1});

  // 2. Lighting: E + island into temp (reading the sky's blocked part there first).
  const shader::TexturePush material{{0.0f, 0.0f, 0.0f, float(object.material)}};
  lighting_.bind(cmd, t.lighting);
  vkCmdPushConstants(cmd, lighting_.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                     sizeof(material), &material);
  Program::dispatch(cmd, t.size, t.size);
  compute_barrier(cmd);

  // 3. Dilation: temp (E), b (stretch) -> irradiance, stretch.
  dilate_.bind(cmd, t.dilate);
  Program::dispatch(cmd, t.size, t.size);
  compute_barrier(cmd);

  // 4. The Gaussians, incrementally: u into temp, v into a / b alternately (+ scattered).
  t.blur.record(cmd, blur_, count, float(object.material), t.size, t.size);
}

void SssTexturePass::add_to(graph::FrameGraph& graph, const MaterialData& materials) {
  // The frame's images it reads: the shadow maps (texture_lighting.comp). Its atlases
  // persist from frame to frame and keep their own barriers (update()).
  const FrameTargets& f = r_.targets;
  graph.add_pass(kName).step(
      {{&f.shadow, graph::use::kSampled}, {&f.light_depth, graph::use::kSampled}},
      [this, &materials](VkCommandBuffer cmd) {
        for (std::size_t i = 0; i < objects_.size(); ++i) {
          Textures& t = textures_[i];
          if (!t.dirty && objects_[i].options.update == TextureUpdate::OnChange) continue;
          const std::uint32_t m = objects_[i].material;
          update(cmd, t, objects_[i], materials.gaussian_count(m));
          t.dirty = false;
          ++objects_[i].updates;
        }
        // The lookups (TextureGatherPass, fragment shader) after this frame's updates, and
        // after earlier frames' for objects not updated now.
        const VkMemoryBarrier2 done = vk::memory_barrier(
            {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT},
            {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT});
        vk::pipeline_barrier(cmd, {}, {}, {&done, 1});
      });
}

}  // namespace sss::renderer
