// The frame end to end on lavapipe: builtin:sphere renders something sensible, cleanly
// (validation, core + synchronization, reports nothing), and deterministically.
#include "RenderTest.h"

#include "scene/BuiltinScenes.h"
#include "scene/Environment.h"

#include <gtest/gtest.h>

#include <cstring>

namespace sss::renderer::testing {
namespace {

TEST_F(RenderTest, SphereRendersLitGeometryOnABlackBackground) {
  const scene::Scene scene = scene::sphere_scene();
  const Frame f = render(scene, small_options(160, 90));
  ASSERT_EQ(f.hdr.width, 160);
  ASSERT_EQ(f.hdr.height, 90);
  int geometry = 0, lit = 0;
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 160; ++x) {
      const float* p = f.hdr.pixel(x, y);
      for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c])) << x << "," << y;
      if (p[3] > 0.5f) {
        ++geometry;
        if (luminance(p) > 0.01f) ++lit;
      } else {
        EXPECT_EQ(luminance(p), 0.0f) << "background at " << x << "," << y;
      }
    }
  // The sphere covers a fair part of the frame and its lit side is not black.
  EXPECT_GT(geometry, 160 * 90 / 20);
  EXPECT_LT(geometry, 160 * 90 / 2);
  EXPECT_GT(lit, geometry / 4);
  // The centre pixel is on the sphere; the corners are background.
  EXPECT_GT(f.hdr.pixel(80, 45)[3], 0.5f);
  EXPECT_EQ(f.hdr.pixel(0, 0)[3], 0.0f);
  // Display values are in [0, 1] and brighter where the radiance is.
  EXPECT_GT(f.display.pixel(80, 45)[0], 0.0f);
  EXPECT_LE(f.display.pixel(80, 45)[0], 1.0f);
}

TEST_F(RenderTest, StatsNamePassesInFrameOrder) {
  const Frame f = render(scene::sphere_scene(), small_options(64, 36, SssTechnique::Separable));
  std::vector<std::string> names;
  for (const vk::PassTime& p : f.stats.passes) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"shadow", "gbuffer", "lighting", "sss separable",
                                             "composite"}));
  EXPECT_GT(f.stats.cpu_ms, 0.0);
}

TEST_F(RenderTest, RenderingIsDeterministic) {
  const scene::Scene scene = scene::sphere_scene();
  for (SssTechnique kind : {SssTechnique::Separable, SssTechnique::Gaussians}) {
    const RenderOptions o = small_options(160, 90, kind);
    const Frame a = render(scene, o);
    const Frame b = render(scene, o, 2);
    ASSERT_EQ(a.hdr.rgba.size(), b.hdr.rgba.size());
    EXPECT_EQ(std::memcmp(a.hdr.rgba.data(), b.hdr.rgba.data(), a.hdr.rgba.size() * sizeof(float)),
              0)
        << technique_name(kind);
    EXPECT_EQ(a.display.rgba, b.display.rgba);
  }
}

// Pre/post albedo (sqrt(albedo) before and after scattering) changes only what the
// scattering spreads: without SSS it equals post-scatter albedo (sqrt a sqrt a = a, to
// the float rounding of the irradiance), with SSS the colour bleeds less across an albedo
// edge. (Under a uniform albedo sqrt(a) is a constant factor that commutes with the blur,
// so the two modes agree there too: the SSS half needs a texture.)
TEST_F(RenderTest, PrePostAlbedoEqualsPostScatterWithoutScattering) {
  scene::Scene post = scene::sphere_scene();
  post.materials[0].base_color = glm::vec4(0.9f, 0.4f, 0.3f, 1.0f);
  scene::Scene pre_post = post;
  pre_post.materials[0].sss.albedo_mode = scene::AlbedoMode::PrePost;
  const Frame a = render(post, small_options(96, 54, SssTechnique::Off));
  const Frame b = render(pre_post, small_options(96, 54, SssTechnique::Off));
  for (std::size_t i = 0; i < a.hdr.rgba.size(); ++i)
    ASSERT_NEAR(a.hdr.rgba[i], b.hdr.rgba[i], 1e-3f * std::fabs(a.hdr.rgba[i]) + 1e-7f) << i;

  // The edge scene's slab maps uv 0..1 across its 200 mm: a 2x2 red / white texture puts an
  // albedo edge at the centre of the view, inside the light.
  scene::Scene edge_post = scene::edge_scene();
  edge_post.lights[0].mask.reset();
  auto image = std::make_shared<scene::ImageRgba8>();
  image->width = image->height = 2;
  image->pixels = {255, 40, 40, 255, 255, 255, 255, 255, 255, 40, 40, 255, 255, 255, 255, 255};
  scene::Texture texture;
  texture.image = image;
  texture.sampler.mag = texture.sampler.min = scene::Filter::Nearest;
  texture.sampler.wrap_s = texture.sampler.wrap_t = scene::Wrap::ClampToEdge;
  edge_post.textures.push_back(texture);
  edge_post.materials[0].base_color_texture = 0;
  scene::Scene edge_pre_post = edge_post;
  edge_pre_post.materials[0].sss.albedo_mode = scene::AlbedoMode::PrePost;
  const Frame c = render(edge_post, small_options(96, 54, SssTechnique::Separable));
  const Frame d = render(edge_pre_post, small_options(96, 54, SssTechnique::Separable));
  double diff = 0.0;
  for (std::size_t i = 0; i < c.hdr.rgba.size(); ++i) diff += std::fabs(c.hdr.rgba[i] - d.hdr.rgba[i]);
  EXPECT_GT(diff, 1e-3);
}

// A frame holds only the targets its technique and view read (FrameTargets::Use); the
// others are 1 x 1. Bytes per pixel of the optional ones (FrameTargets.h's formats): sss
// temp, a, b and accum rgba16f (8 each), sss line and prefix rgba32f (16 each), uv stretch
// and sky blocked rgba16f (8 each), the display source rgba8 (4). The device rounds each
// image's memory up to its VkMemoryRequirements alignment (tiling padding included); 64
// KiB, the largest page alignment Vulkan devices ask for an image, bounds that per image,
// over the 16 images.
TEST_F(RenderTest, AFrameHoldsOnlyTheTargetsItsTechniqueReads) {
  const std::uint32_t w = 320, h = 180;
  const double px = double(w) * double(h);
  const double slack = 16.0 * 65536.0;
  const FrameTargets all(ctx(), w, h, 1, 512, FrameTargets::Use{});
  const double full = double(all.memory_bytes());
  struct Row {
    SssTechnique technique;
    DebugView view;
    Antialias aa;
    double unread_bytes_per_px;  // of the optional targets, those this frame does not read
    bool environment = false;    // the sky target (8 bytes a pixel) is read with one
  };
  const Row rows[] = {
      {SssTechnique::Off, DebugView::None, Antialias::Off, 4 * 8 + 2 * 16 + 8 + 4 + 8},
      {SssTechnique::Separable, DebugView::None, Antialias::Off, 4 * 8 + 8 + 4 + 8},
      {SssTechnique::Separable, DebugView::None, Antialias::Off, 4 * 8 + 8 + 4, true},
      {SssTechnique::Separable, DebugView::Scattered, Antialias::Off, 3 * 8 + 8 + 4 + 8},
      {SssTechnique::Separable, DebugView::None, Antialias::Fxaa, 4 * 8 + 8 + 8},
      {SssTechnique::Gaussians, DebugView::None, Antialias::Off, 2 * 16 + 8 + 4 + 8},
      {SssTechnique::Texture, DebugView::None, Antialias::Off, 3 * 8 + 2 * 16 + 8 + 4 + 8},
      {SssTechnique::Texture, DebugView::None, Antialias::Off, 3 * 8 + 2 * 16 + 8 + 4, true},
      // The uv-stretch view takes the G-buffer's third attachment: no sky target.
      {SssTechnique::Texture, DebugView::UvStretch, Antialias::Off, 3 * 8 + 2 * 16 + 4 + 8, true},
  };
  for (const Row& row : rows) {
    RenderOptions o = small_options(w, h, row.technique);
    o.debug_view = row.view;
    o.antialias = row.aa;
    const FrameTargets t(ctx(), w, h, 1, 512, FrameTargets::use_for(o, row.environment));
    const double saved = full - double(t.memory_bytes());
    const std::string what = std::string(technique_name(row.technique)) + " " +
                             std::string(debug_view_name(row.view)) + " " +
                             std::string(antialias_name(row.aa));
    EXPECT_NEAR(saved, row.unread_bytes_per_px * px, slack) << what;
    // The renderer holds these targets, and switching to the row's options from the
    // default changes them to these.
    scene::Scene sphere = scene::sphere_scene();
    if (row.environment) sphere.environment = scene::uniform_environment({0.3f, 0.3f, 0.3f});
    Renderer r(ctx(), sphere, small_options(w, h, SssTechnique::Separable));
    r.set_options(o);
    EXPECT_EQ(r.target_bytes(), t.memory_bytes()) << what << (row.environment ? " environment" : "");
  }
}

}  // namespace
}  // namespace sss::renderer::testing
