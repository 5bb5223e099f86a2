// Several SSS materials in one frame (builtin:materials: one sphere per usable preset,
// each its own profile): every sphere renders, with its own colour, and screen-space
// SSS changes every sphere (each material's kernel is used, not the first one's).
#include "RenderTest.h"

#include "renderer/CameraSetup.h"
#include "scene/BuiltinScenes.h"

#include <gtest/gtest.h>

#include <glm/vec4.hpp>

#include <cmath>

namespace sss::renderer::testing {
namespace {

TEST_F(RenderTest, SeveralMaterialsInOneFrameEachWithItsOwnProfile) {
  const scene::Scene s = scene::materials_scene();
  ASSERT_GE(s.materials.size(), 8u);
  const std::uint32_t w = 320, h = 180;
  const Frame off = render(s, small_options(w, h, SssTechnique::Off));
  const Frame sep = render(s, small_options(w, h, SssTechnique::Separable));
  const Frame gau = render(s, small_options(w, h, SssTechnique::Gaussians));
  ASSERT_EQ(sep.materials.profiles.size(), s.materials.size());

  const CameraSetup cam = make_camera_setup(s.cameras.front(), w, h);
  std::vector<std::array<float, 3>> colours;
  for (const scene::Instance& inst : s.instances) {
    const glm::vec4 clip = cam.proj * cam.view * inst.world * glm::vec4(0, 0, 0, 1);
    const int px = int((clip.x / clip.w * 0.5f + 0.5f) * float(w));
    const int py = int((clip.y / clip.w * 0.5f + 0.5f) * float(h));
    ASSERT_TRUE(px >= 0 && px < int(w) && py >= 0 && py < int(h)) << inst.node;
    // Mean over a 5x5 patch at the sphere's centre.
    std::array<float, 3> mean{};
    double change_sep = 0.0, change_gau = 0.0;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const float* p = off.hdr.pixel(px + dx, py + dy);
        ASSERT_GT(p[3], 0.5f) << inst.node << " is not at its projected centre";
        for (int c = 0; c < 3; ++c) mean[c] += p[c] / 25.0f;
        for (int c = 0; c < 3; ++c) {
          change_sep += std::fabs(sep.hdr.pixel(px + dx, py + dy)[c] - p[c]);
          change_gau += std::fabs(gau.hdr.pixel(px + dx, py + dy)[c] - p[c]);
        }
      }
    EXPECT_GT(mean[0] + mean[1] + mean[2], 1e-3f) << inst.node << " is black";
    // Scattering moves light around on every sphere (the patch straddles the shading
    // gradient of the key light).
    EXPECT_GT(change_sep, 1e-5) << inst.node;
    EXPECT_GT(change_gau, 1e-5) << inst.node;
    colours.push_back(mean);
  }
  // Each sphere's colour differs from every other one's (by >= 1% in some channel).
  for (std::size_t i = 0; i < colours.size(); ++i)
    for (std::size_t j = i + 1; j < colours.size(); ++j) {
      float d = 0.0f;
      for (int c = 0; c < 3; ++c)
        d = std::max(d, std::fabs(colours[i][c] - colours[j][c]) /
                            std::max(colours[i][c], colours[j][c]));
      EXPECT_GT(d, 0.01f) << s.instances[i].node << " vs " << s.instances[j].node;
    }
}

}  // namespace
}  // namespace sss::renderer::testing
