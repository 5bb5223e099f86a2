// The fixture of the renderer tests: the renderer/vk fixture (lavapipe, validation with
// the checks SSS_VALIDATION_CHECKS names, core + synchronization by default; any message
// fails the test) plus a helper that renders a scene headlessly and reads the frame back.
#pragma once

#include "vk/VulkanTest.h"

#include "renderer/Renderer.h"
#include "image/Image.h"
#include "scene/Scene.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <array>
#include <cmath>

namespace sss::renderer::testing {

struct Frame {
  image::Image hdr;      // linear radiance
  image::Image display;  // tonemapped, sRGB codes / 255
  FrameStats stats;
  MaterialData materials;  // the fits and kernels the frame used
  image::Image specular;   // the specular radiance in hdr (Renderer::read_specular)
  std::array<float, 2> debug_range{};  // Renderer::debug_range() of the frame
};

class RenderTest : public vk::testing::VulkanTest {
 protected:
  Frame render(const scene::Scene& scene, const RenderOptions& options, int frames = 1) {
    EXPECT_TRUE(ctx().validation_enabled()) << "the validation layer is not installed";
    Renderer renderer(ctx(), scene, options);
    for (int i = 0; i < frames; ++i) renderer.render_frame();
    return {renderer.read_hdr(), renderer.read_display(), renderer.stats(), renderer.materials(),
            renderer.read_specular(), renderer.debug_range()};
  }
};

inline RenderOptions small_options(std::uint32_t w, std::uint32_t h,
                                   SssTechnique technique = SssTechnique::Off) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.technique = technique;
  o.shadow_map_size = 512;
  return o;
}

inline float luminance(const float* p) { return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]; }

// Makes `cam` a perspective camera height_mm above the origin looking straight down -y
// (image up = -z), whose field of view spans [-half_width_mm, half_width_mm] of the y = 0
// plane across an image of `aspect` (width / height); near and far at 0.1 and 10 x the
// height. Scenes in metres (mm_per_unit 1000), as builtin:edge.
inline void look_straight_down(scene::Camera& cam, double height_mm, double half_width_mm, double aspect) {
  cam.projection = scene::Projection::Perspective;
  cam.yfov = float(2.0 * std::atan(half_width_mm / height_mm / aspect));
  cam.aspect = 0.0f;
  cam.znear = float(0.1 * height_mm * 1e-3);
  cam.zfar = float(10.0 * height_mm * 1e-3);
  cam.world = scene::look_at_world({0.0f, float(height_mm * 1e-3), 0.0f}, glm::vec3(0.0f), {0.0f, 0.0f, -1.0f});
}

// The unit world direction of the ray through the centre of pixel (x, y) of a w x h image
// from a perspective camera whose aspect follows the image (camera looks down -z, image y
// down), from its field of view alone: what a test checks the renderer's projection with.
inline glm::vec3 pixel_ray(const scene::Camera& cam, int x, int y, int w, int h) {
  const double t = std::tan(0.5 * double(cam.yfov)), aspect = double(w) / h;
  const glm::vec3 d(float((2.0 * (x + 0.5) / w - 1.0) * t * aspect), float((1.0 - 2.0 * (y + 0.5) / h) * t), -1.0f);
  return glm::normalize(glm::mat3(cam.world) * d);
}

}  // namespace sss::renderer::testing
