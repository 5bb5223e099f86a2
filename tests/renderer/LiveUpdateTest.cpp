// A live Renderer changed between frames (what the viewer does) draws the same frame as
// a Renderer constructed with the changed input: camera, lights (moved, brighter, one
// more), materials (another preset and model), options (SSS mode and kind, taps,
// exposure), size (and back), several at once. The frames are compared bit for bit, HDR
// and display: a live change rebuilds exactly the uniforms, tables and targets the
// constructor builds, and lavapipe is deterministic (RenderingIsDeterministic). Extra
// shadow layers kept after a light is removed are cleared and never sampled. All under
// validation with synchronization checks (the fixture fails on any message).
#include "RenderTest.h"

#include "scene/BuiltinScenes.h"
#include "scene/Camera.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <variant>

namespace sss::renderer::testing {
namespace {

constexpr std::uint32_t kW = 96, kH = 54;

class LiveUpdateTest : public RenderTest {
 protected:
  // The live renderer's last frame equals a fresh renderer's first frame of `scene`
  // with `options`, bit for bit.
  void expect_fresh(const Renderer& live, const scene::Scene& scene, const RenderOptions& options,
                    const std::string& what) {
    const Frame fresh = render(scene, options);
    const image::Image hdr = live.read_hdr();
    const image::Image display = live.read_display();
    ASSERT_EQ(hdr.width, fresh.hdr.width) << what;
    ASSERT_EQ(hdr.height, fresh.hdr.height) << what;
    int differing = 0;
    float max_diff = 0.0f;
    for (std::size_t i = 0; i < hdr.rgba.size(); ++i)
      if (std::memcmp(&hdr.rgba[i], &fresh.hdr.rgba[i], sizeof(float)) != 0) {
        ++differing;
        max_diff = std::max(max_diff, std::fabs(hdr.rgba[i] - fresh.hdr.rgba[i]));
      }
    EXPECT_EQ(differing, 0) << what << ": " << differing << " HDR values differ, max " << max_diff;
    EXPECT_EQ(display.rgba, fresh.display.rgba) << what;
    EXPECT_EQ(live.materials().gpu.size(), fresh.materials.gpu.size()) << what;
  }
};

scene::Camera orbited(const scene::Camera& camera, float angle, float zoom) {
  scene::Camera c = camera;
  const glm::vec3 eye = glm::vec3(glm::rotate(glm::mat4(1.0f), angle, {0.0f, 1.0f, 0.0f}) *
                                  glm::vec4(camera.position() * zoom, 1.0f));
  c.world = scene::look_at_world(eye, glm::vec3(0.0f), {0.0f, 1.0f, 0.0f});
  return c;
}

scene::Material marble_pbd(scene::Material m) {
  m.sss = std::get<scene::SssMaterial>(
      scene::make_sss_material(scene::PresetSource{"marble"}, profiles::Model::Pbd));
  m.base_color = glm::vec4(0.85f, 0.8f, 0.75f, 1.0f);
  m.roughness = 0.3f;
  return m;
}

scene::Light spot_light() {
  scene::Light l;
  l.name = "spot";
  l.type = scene::LightType::Spot;
  l.intensity = 0.02f;  // W/sr at 0.2 m: E = 0.5
  l.color = {1.0f, 0.8f, 0.6f};
  l.outer_cone = 0.4f;
  l.inner_cone = 0.2f;
  l.world = scene::look_at_world({0.15f, 0.1f, 0.1f}, glm::vec3(0.0f), {0.0f, 1.0f, 0.0f});
  return l;
}

TEST_F(LiveUpdateTest, SetCameraEqualsAFreshRenderer) {
  scene::Scene scene = scene::sphere_scene();
  const RenderOptions o = small_options(kW, kH, SssTechnique::Separable);
  Renderer live(ctx(), scene, o);
  live.render_frame();
  for (const float angle : {0.5f, -1.2f}) {
    scene.cameras[0] = orbited(scene.cameras[0], angle, 1.3f);
    live.set_camera(scene.cameras[0]);
    live.render_frame();
    expect_fresh(live, scene, o, "orbit " + std::to_string(angle));
  }
  // An orthographic camera (the SSS kernel width follows xmag, not depth).
  scene.cameras[0].projection = scene::Projection::Orthographic;
  scene.cameras[0].xmag = 0.05f;
  scene.cameras[0].znear = 0.0f;
  live.set_camera(scene.cameras[0]);
  live.render_frame();
  expect_fresh(live, scene, o, "orthographic");
}

// builtin:sphere plus a 9 mm sphere between spot_light() and the big sphere, so that the
// spot's shadow map shows in the frame.
scene::Scene sphere_with_blocker() {
  scene::Scene scene = scene::sphere_scene();
  const glm::mat4 world = glm::scale(glm::translate(glm::mat4(1.0f), {0.0675f, 0.045f, 0.045f}),
                                     glm::vec3(0.3f));
  scene.instances.push_back({0, world, "blocker"});
  return scene;
}

TEST_F(LiveUpdateTest, SetLightsEqualsAFreshRenderer) {
  scene::Scene scene = sphere_with_blocker();
  const RenderOptions o = small_options(kW, kH, SssTechnique::Separable);
  Renderer live(ctx(), scene, o);
  live.render_frame();

  scene.lights[0].world = glm::rotate(glm::mat4(1.0f), 0.7f, {0.0f, 1.0f, 0.0f}) *
                          scene.lights[0].world;
  live.set_lights(scene.lights);
  live.render_frame();
  expect_fresh(live, scene, o, "moved");

  scene.lights[0].intensity *= 1.7f;
  live.set_lights(scene.lights);
  live.render_frame();
  expect_fresh(live, scene, o, "brighter");

  scene.lights.push_back(spot_light());  // a second shadow layer
  live.set_lights(scene.lights);
  live.render_frame();
  expect_fresh(live, scene, o, "second light");

  scene.lights.erase(scene.lights.begin());  // back to one light, two layers kept
  live.set_lights(scene.lights);
  live.render_frame();
  expect_fresh(live, scene, o, "first light removed");
  EXPECT_TRUE(live.warnings().empty());
}

TEST_F(LiveUpdateTest, SetMaterialsEqualsAFreshRenderer) {
  const scene::Scene skin = scene::sphere_scene();
  scene::Scene marble = skin;
  marble.materials[0] = marble_pbd(marble.materials[0]);
  for (SssTechnique kind : {SssTechnique::Separable, SssTechnique::Gaussians}) {
    const RenderOptions o = small_options(kW, kH, kind);
    Renderer live(ctx(), skin, o);
    live.render_frame();
    live.set_materials(marble.materials);
    live.render_frame();
    expect_fresh(live, marble, o, std::string("marble pbd, ") + std::string(technique_name(kind)));
    live.set_materials(skin.materials);
    live.render_frame();
    expect_fresh(live, skin, o, std::string("skin1 again, ") + std::string(technique_name(kind)));
  }
}

TEST_F(LiveUpdateTest, SetMaterialsRejectsAnotherCountOrOtherTextures) {
  const scene::Scene scene = scene::sphere_scene();
  const RenderOptions o = small_options(kW, kH, SssTechnique::Separable);
  Renderer live(ctx(), scene, o);
  std::vector<scene::Material> two = {scene.materials[0], scene.materials[0]};
  EXPECT_THROW(live.set_materials(two), std::invalid_argument);
  std::vector<scene::Material> textured = scene.materials;
  textured[0].base_color_texture = 0;
  EXPECT_THROW(live.set_materials(textured), std::invalid_argument);
  live.render_frame();
  expect_fresh(live, scene, o, "after the rejected materials");
}

// The single-scattering switch refits every material (profiles with or without their
// once-scattered light): toggling it live gives the frame a fresh renderer makes, in the
// screen and the texture path (whose atlases hold blurred light of the old profile, so
// they must be made again even with the on-change policy).
TEST_F(LiveUpdateTest, SingleScatteringSwitchRefitsAndRebuildsTheAtlases) {
  const scene::Scene scene = scene::sphere_scene();
  for (const SssTechnique mode : {SssTechnique::Gaussians, SssTechnique::Texture}) {
    RenderOptions o = small_options(kW, kH, mode);
    Renderer live(ctx(), scene, o);
    live.render_frame();
    for (const bool single : {!o.single_scattering, o.single_scattering}) {
      o.single_scattering = single;
      live.set_options(o);
      live.render_frame();
      EXPECT_EQ(live.materials().single_scattering, single);
      expect_fresh(live, scene, o, std::string(technique_name(mode)) + (single ? " S(1) on" : " S(1) off"));
    }
  }
}

TEST_F(LiveUpdateTest, SetOptionsSwitchesSssTechniques) {
  const scene::Scene scene = scene::sphere_scene();
  RenderOptions o = small_options(kW, kH, SssTechnique::Separable);
  Renderer live(ctx(), scene, o);
  live.render_frame();
  // Every technique from every other (the viewer's combo): each pair appears as a step.
  const SssTechnique steps[] = {SssTechnique::Gaussians, SssTechnique::Off,       SssTechnique::Separable,
                                SssTechnique::Texture,   SssTechnique::Gaussians, SssTechnique::Texture,
                                SssTechnique::Off,       SssTechnique::Texture,   SssTechnique::Separable,
                                SssTechnique::Off,       SssTechnique::Gaussians, SssTechnique::Separable};
  for (const SssTechnique step : steps) {
    o.technique = step;
    live.set_options(o);
    live.render_frame();
    expect_fresh(live, scene, o, std::string(technique_name(step)));
  }
  o.separable_taps = 9;
  o.exposure = 2.5f;
  live.set_options(o);
  live.render_frame();
  expect_fresh(live, scene, o, "9 taps, exposure 2.5");
  EXPECT_EQ(live.materials().profiles[0]->kernel.offsets_mm.size(), 9u);

  o.shadow_map_size = 256;
  live.set_options(o);
  live.render_frame();
  expect_fresh(live, scene, o, "shadow map 256");

  RenderOptions bad = o;
  bad.separable_taps = 4;
  EXPECT_THROW(live.set_options(bad), std::invalid_argument);
  bad = o;
  bad.shadow_map_size = 0;
  EXPECT_THROW(live.set_options(bad), std::invalid_argument);
  live.render_frame();
  expect_fresh(live, scene, o, "after the rejected options");
}

TEST_F(LiveUpdateTest, ResizeAndBack) {
  const scene::Scene scene = scene::sphere_scene();
  for (SssTechnique kind : {SssTechnique::Separable, SssTechnique::Gaussians}) {
    RenderOptions o = small_options(kW, kH, kind);
    Renderer live(ctx(), scene, o);
    live.render_frame();
    live.resize(97, 61);
    live.render_frame();
    EXPECT_EQ(live.display_image().width(), 97u);
    EXPECT_EQ(live.display_image().height(), 61u);
    EXPECT_EQ(live.options().width, 97u);
    o.width = 97;
    o.height = 61;
    expect_fresh(live, scene, o, "97x61 " + std::string(technique_name(kind)));
    live.resize(kW, kH);
    live.render_frame();
    o.width = kW;
    o.height = kH;
    expect_fresh(live, scene, o, "back to 96x54 " + std::string(technique_name(kind)));
    EXPECT_EQ(live.display_image().width(), kW);
    EXPECT_EQ(Renderer::display_layout(), VK_IMAGE_LAYOUT_GENERAL);
  }
}

TEST_F(LiveUpdateTest, SeveralChangesThenOneFrame) {
  scene::Scene scene = scene::sphere_scene();
  RenderOptions o = small_options(kW, kH, SssTechnique::Separable);
  Renderer live(ctx(), scene, o);
  live.render_frame();

  scene.cameras[0] = orbited(scene.cameras[0], 0.8f, 1.1f);
  live.set_camera(scene.cameras[0]);
  scene.lights.push_back(spot_light());
  live.set_lights(scene.lights);
  scene.materials[0] = marble_pbd(scene.materials[0]);
  live.set_materials(scene.materials);
  o.technique = SssTechnique::Gaussians;
  o.exposure = 1.5f;
  live.set_options(o);
  live.resize(97, 61);
  o.width = 97;
  o.height = 61;
  live.set_camera(scene.cameras[0]);  // the same camera again, at the new aspect
  live.render_frame();
  expect_fresh(live, scene, o, "camera + lights + materials + options + size");
}

TEST_F(LiveUpdateTest, ZeroSizeResizeThrowsAndLeavesTheRendererUsable) {
  const scene::Scene scene = scene::sphere_scene();
  const RenderOptions o = small_options(kW, kH, SssTechnique::Separable);
  Renderer live(ctx(), scene, o);
  live.render_frame();
  EXPECT_THROW(live.resize(0, kH), std::invalid_argument);
  EXPECT_THROW(live.resize(kW, 0), std::invalid_argument);
  EXPECT_THROW(live.resize(0, 0), std::invalid_argument);
  RenderOptions zero = o;
  zero.width = 0;
  EXPECT_THROW(live.set_options(zero), std::invalid_argument);
  // Past the device's maxImageDimension2D (lavapipe: 16384) or the renderer's own 16384.
  const std::uint32_t limit = std::min<std::uint32_t>(ctx().info().limits.maxImageDimension2D, 16384);
  EXPECT_THROW(live.resize(limit + 1, kH), std::invalid_argument);
  EXPECT_THROW(live.resize(kW, limit + 1), std::invalid_argument);
  EXPECT_EQ(live.options().width, kW);
  EXPECT_EQ(live.options().height, kH);
  live.render_frame();
  expect_fresh(live, scene, o, "after the rejected sizes");
}

}  // namespace
}  // namespace sss::renderer::testing
