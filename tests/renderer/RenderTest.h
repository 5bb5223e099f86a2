// The fixture of the renderer tests: the renderer/vk fixture (lavapipe, validation with
// the checks SSS_VALIDATION_CHECKS names, core + synchronization by default; any message
// fails the test) plus a helper that renders a scene headlessly and reads the frame back.
#pragma once

#include "vk/VulkanTest.h"

#include "renderer/Renderer.h"
#include "renderer/image/Image.h"
#include "renderer/scene/Scene.h"

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

inline RenderOptions small_options(std::uint32_t w, std::uint32_t h, SssMode sss = SssMode::Off,
                                   SssKind kind = SssKind::Separable) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.sss = sss;
  o.kind = kind;
  o.shadow_map_size = 512;
  return o;
}

inline float luminance(const float* p) { return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]; }

}  // namespace sss::renderer::testing
