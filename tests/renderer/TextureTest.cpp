// Material textures in the G-buffer: a base colour texture (sRGB) and a normal map on the
// builtin:edge slab, fully lit at normal incidence, seen straight down (x, z in +-20 mm).
#include "RenderTest.h"

#include "scene/BuiltinScenes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <set>

namespace sss::renderer::testing {
namespace {

constexpr float kPi = 3.14159265f;

scene::Scene lit_slab() {
  scene::Scene s = scene::edge_scene();
  s.lights[0].mask.reset();  // lit everywhere, E = 1
  s.materials[0].sss = scene::SssMaterial{};
  return s;
}

std::uint32_t add_texture(scene::Scene& s, std::uint32_t w, std::uint32_t h,
                          std::vector<std::uint8_t> pixels) {
  auto image = std::make_shared<scene::ImageRgba8>();
  image->width = w;
  image->height = h;
  image->pixels = std::move(pixels);
  scene::Texture t;
  t.name = "test texture";
  t.image = image;
  t.sampler.mag = t.sampler.min = scene::Filter::Nearest;
  t.sampler.wrap_s = t.sampler.wrap_t = scene::Wrap::ClampToEdge;
  s.textures.push_back(t);
  return static_cast<std::uint32_t>(s.textures.size() - 1);
}

TEST_F(RenderTest, BaseColourTextureColoursTheAlbedo) {
  // The slab's top face maps uv 0..1 across its 200 mm, so the view (+-20 mm around the
  // centre) sees the four texels of a 2x2 texture meet in the middle.
  scene::Scene s = lit_slab();
  s.materials[0].base_color_texture = add_texture(
      s, 2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255});
  const int n = 64;
  const Frame f = render(s, small_options(n, n));
  std::set<std::array<int, 3>> seen;
  for (int qy : {n / 4, 3 * n / 4})
    for (int qx : {n / 4, 3 * n / 4}) {
      const float* p = f.hdr.pixel(qx, qy);
      std::array<int, 3> colour{};
      for (int c = 0; c < 3; ++c) {
        const float v = p[c] * kPi;  // albedo x E, E = 1
        EXPECT_TRUE(std::fabs(v) < 1e-4f || std::fabs(v - 1.0f) < 1e-4f) << v;
        colour[c] = v > 0.5f ? 1 : 0;
      }
      seen.insert(colour);
    }
  EXPECT_EQ(seen, (std::set<std::array<int, 3>>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}));
}

TEST_F(RenderTest, NormalMapTiltsTheShadingNormal) {
  // Tangent-space normal (0.71, 0, 0.71): tilted 45 degrees, so E = cos 45 under the
  // normal-incidence light (the tangent direction does not matter).
  scene::Scene s = lit_slab();
  s.materials[0].normal_texture = add_texture(s, 1, 1, {218, 128, 218, 255});
  const Frame f = render(s, small_options(32, 32));
  const float m = (218.0f / 255.0f) * 2.0f - 1.0f, m0 = (128.0f / 255.0f) * 2.0f - 1.0f;
  const float expected = m / std::sqrt(2.0f * m * m + m0 * m0) / kPi;
  EXPECT_NEAR(f.hdr.pixel(16, 16)[0], expected, 1e-3f * expected);
  EXPECT_NEAR(f.hdr.pixel(3, 29)[1], expected, 1e-3f * expected);
}

}  // namespace
}  // namespace sss::renderer::testing
