// builtin:slab, the transmission scene: a thin multipole slab whose thickness is the
// geometry's, lit only from behind, seen from the front (SlabScene.cpp).
#include "scene/BuiltinScenes.h"

#include "profiles/Presets.h"
#include "profiles/Profile.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace sss::scene {
namespace {

Scene slab() {
  auto r = builtin_scene("builtin:slab");
  if (auto* e = std::get_if<LoadError>(&r)) ADD_FAILURE() << e->what();
  return r.index() == 0 ? std::get<Scene>(std::move(r)) : Scene{};
}

TEST(SlabScene, IsRegisteredAndLoads) {
  const auto names = builtin_scene_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "builtin:slab"), names.end());
  const Scene s = slab();
  EXPECT_EQ(s.name, "builtin:slab");
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 1u);
  ASSERT_EQ(s.materials.size(), 1u);
  ASSERT_EQ(s.cameras.size(), 1u);
  ASSERT_EQ(s.lights.size(), 1u) << "no fill light: the front shows transmission only";
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(check_mesh(s.meshes[0]), std::nullopt);
  EXPECT_EQ(s.meshes[0].indices.size(), 36u);  // a box: 12 triangles, cheap
  EXPECT_DOUBLE_EQ(s.mm_per_unit, 1000.0);
}

TEST(SlabScene, MaterialIsAMultipoleSlabAsThickAsTheGeometry) {
  const Scene s = slab();
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  ASSERT_TRUE(m.sss.enabled);
  EXPECT_EQ(m.sss.model, profiles::Model::Multipole);
  EXPECT_DOUBLE_EQ(m.sss.scale, 1.0);
  EXPECT_EQ(m.sss.albedo_mode, AlbedoMode::PostScatter);
  EXPECT_EQ(m.specular, 0.0f);  // all the light reaching the back face enters
  EXPECT_EQ(m.base_color, glm::vec4(1.0f));

  // The thinnest extent of the box, in mm, is the slab's thickness.
  const Bounds b = s.bounds();
  const glm::vec3 extent_mm = b.extent() * float(s.mm_per_unit);
  const float thickness_mm = std::min({extent_mm.x, extent_mm.y, extent_mm.z});
  EXPECT_NEAR(thickness_mm, 2.0f, 1e-4f);
  EXPECT_NEAR(extent_mm.x, 30.0f, 1e-3f);
  EXPECT_NEAR(extent_mm.y, 30.0f, 1e-3f);

  ASSERT_TRUE(m.sss.medium.is_slab());
  EXPECT_NEAR(m.sss.medium.thickness_mm, thickness_mm, 1e-4);
  EXPECT_NEAR(m.sss.effective_medium().thickness_mm, thickness_mm, 1e-4);
  // The source is the preset's coefficients with the thickness, and resolves to itself.
  const auto* src = std::get_if<CoefficientSource>(&m.sss.source);
  ASSERT_NE(src, nullptr);
  EXPECT_DOUBLE_EQ(src->medium.thickness_mm, m.sss.medium.thickness_mm);
  const profiles::Medium preset = profiles::preset_medium(*profiles::find_preset("skin2"));
  for (int c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(m.sss.medium.sigma_a[c], preset.sigma_a[c]);
    EXPECT_DOUBLE_EQ(m.sss.medium.sigma_s[c], preset.sigma_s[c]);
    EXPECT_DOUBLE_EQ(m.sss.medium.eta[c], preset.eta[c]);
    // The multipole needs the slab to be thicker than one reduced mean free path; the
    // scene keeps it at two or more, where the model is trustworthy.
    EXPECT_GT(thickness_mm, 2.0 * m.sss.medium.channel(c).mfp_reduced()) << c;
  }
  // Cheap for the CPU reference: the SSS area is small next to mfp² × 1e5 (mm²).
  double area_mm2 = 0.0;
  const Mesh& mesh = s.meshes[0];
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[i]], b2 = mesh.positions[mesh.indices[i + 1]],
                    c2 = mesh.positions[mesh.indices[i + 2]];
    area_mm2 += 0.5 * glm::length(glm::cross(b2 - a, c2 - a)) * s.mm_per_unit * s.mm_per_unit;
  }
  EXPECT_NEAR(area_mm2, 2 * 30 * 30 + 4 * 30 * 2, 0.1);
  for (int c = 0; c < 3; ++c) {
    const double mfp = m.sss.effective_medium().channel(c).mfp_reduced();
    EXPECT_LT(area_mm2, 0.1 * mfp * mfp * 1e5) << "channel " << c;
  }
  const profiles::RgbProfile profile(m.sss.model, m.sss.effective_medium());
  const auto t = profile.total_transmittance();
  for (int c = 0; c < 3; ++c) EXPECT_GT(t[c], 0.1) << "channel " << c << " barely transmits";
  EXPECT_GT(t[0], t[1]);  // red comes through best
  EXPECT_GT(t[1], t[2]);
}

TEST(SlabScene, LightComesFromBehindAndTheCameraSeesTheUnlitFace) {
  const Scene s = slab();
  ASSERT_EQ(s.cameras.size(), 1u);
  ASSERT_EQ(s.lights.size(), 1u);
  const Camera& cam = s.cameras[0];
  const Light& light = s.lights[0];
  EXPECT_EQ(light.type, LightType::Directional);
  EXPECT_FALSE(light.mask.has_value());
  EXPECT_GT(light.intensity, 0.0f);

  // The slab's two large faces are z = ±1 mm with normals ±z; the camera is on the +z
  // side, so the front face (the one it sees) has the outward normal +z.
  const Mesh& mesh = s.meshes[0];
  const glm::vec3 front(0, 0, 1);
  const Bounds b = s.bounds();
  EXPECT_GT(cam.position().z, b.max.z);
  // The camera looks at the front face: toward it, at the slab's centre, slightly
  // obliquely (between 5 and 30 degrees off the normal).
  const float cos_view = glm::dot(cam.forward(), -front);
  EXPECT_GT(cos_view, std::cos(glm::radians(30.0f)));
  EXPECT_LT(cos_view, std::cos(glm::radians(5.0f)));
  const glm::vec3 to_center = glm::normalize(b.center() - cam.position());
  EXPECT_NEAR(glm::dot(cam.forward(), to_center), 1.0f, 1e-5f);
  // The whole front face is in a 16:9 frame (the golden frames' 160 x 90), and fills
  // more than half its height.
  const glm::mat4 clip = clip_from_view(cam, 160, 90) * cam.view();
  float y_lo = 1.0f, y_hi = -1.0f;
  for (float x : {b.min.x, b.max.x})
    for (float y : {b.min.y, b.max.y}) {
      const glm::vec4 c = clip * glm::vec4(x, y, b.max.z, 1.0f);
      ASSERT_GT(c.w, 0.0f);
      const glm::vec3 ndc = glm::vec3(c) / c.w;
      EXPECT_LT(std::fabs(ndc.x), 0.95f) << x << ", " << y;
      EXPECT_LT(std::fabs(ndc.y), 0.95f) << x << ", " << y;
      EXPECT_GT(ndc.z, 0.0f);
      EXPECT_LT(ndc.z, 1.0f);
      y_lo = std::min(y_lo, ndc.y);
      y_hi = std::max(y_hi, ndc.y);
    }
  EXPECT_GT(y_hi - y_lo, 1.0f);

  // "From behind": the light travels toward the camera's side, i.e. along the front
  // face's outward normal (direction · front > 0). Then the back face (normal -front) is
  // lit at normal incidence, and every face the camera can see gets n · (-direction) <= 0.
  const glm::vec3 d = light.direction();
  EXPECT_GT(glm::dot(d, front), 0.999f);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 n = mesh.normals[v];
    const glm::vec3 p = mesh.positions[v];
    const bool visible = glm::dot(n, cam.position() - p) > 0.0f;  // front-facing to the camera
    const float n_dot_l = glm::dot(n, -d);
    if (visible) {
      EXPECT_LE(n_dot_l, 1e-6f) << "the camera sees a directly lit face at vertex " << v;
    }
    if (n_dot_l > 0.5f) {
      EXPECT_NEAR(glm::dot(n, -front), 1.0f, 1e-6f);  // only the back face is lit
    }
  }
  // The camera sees the front face: it is in front of it, and the face is front-facing.
  EXPECT_GT(glm::dot(front, cam.position() - glm::vec3(0, 0, b.max.z)), 0.0f);
}

}  // namespace
}  // namespace sss::scene
