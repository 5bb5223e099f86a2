// assets/textured_tile.glb (written by assets/make_textured_tile.py) loads cleanly and has
// what a textured SSS test scene needs: UVs and tangents on a closed mesh, a base-colour
// texture and a normal map, an SSS material, its own camera and KHR_lights_punctual light.
#include "scene/GltfLoader.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#ifndef SSS_SOURCE_DIR
#error "SSS_SOURCE_DIR must name the source tree (tests/CMakeLists.txt sets it)"
#endif

namespace sss::scene {
namespace {

const std::string kTile = std::string(SSS_SOURCE_DIR) + "/assets/textured_tile.glb";

Scene load_tile() {
  LoadOptions options;
  options.add_camera_if_missing = false;  // what is there must come from the file
  options.add_light_if_missing = false;
  auto r = load_gltf(kTile, options);
  if (auto* e = std::get_if<LoadError>(&r)) ADD_FAILURE() << e->what();
  return r.index() == 0 ? std::get<Scene>(std::move(r)) : Scene{};
}

TEST(TexturedAsset, LoadsWithoutWarnings) {
  const Scene s = load_tile();
  for (const std::string& w : s.warnings) ADD_FAILURE() << "warning: " << w;
  EXPECT_DOUBLE_EQ(s.mm_per_unit, 1000.0);
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 1u);
  ASSERT_EQ(s.materials.size(), 1u);
  ASSERT_EQ(s.textures.size(), 2u);
  EXPECT_EQ(check_mesh(s.meshes[0]), std::nullopt);
  EXPECT_LE(s.triangle_count(), 1000u);  // cheap for the golden frames
  // A 50 mm tile (metres in the file).
  const Bounds b = s.bounds();
  EXPECT_NEAR(b.extent().x, 0.050f, 1e-4f);
  EXPECT_NEAR(b.extent().z, 0.050f, 1e-4f);
  EXPECT_GT(b.extent().y, 0.006f);  // thickness plus the curve
  EXPECT_LT(b.extent().y, 0.012f);
}

TEST(TexturedAsset, MeshHasUvsAndATangentFrameThatFollowsThem) {
  const Scene s = load_tile();
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.uv0.size(), m.positions.size());
  ASSERT_EQ(m.tangents.size(), m.positions.size());
  glm::vec2 lo(1e9f), hi(-1e9f);
  for (const glm::vec2& uv : m.uv0) {
    lo = glm::min(lo, uv);
    hi = glm::max(hi, uv);
  }
  EXPECT_NEAR(lo.x, 0.0f, 1e-6f);  // the top spans the texture once
  EXPECT_NEAR(lo.y, 0.0f, 1e-6f);
  EXPECT_NEAR(hi.x, 1.0f, 1e-6f);
  EXPECT_NEAR(hi.y, 1.0f, 1e-6f);
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const std::uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
    const glm::vec3 e1 = m.positions[i1] - m.positions[i0], e2 = m.positions[i2] - m.positions[i0];
    const glm::vec3 n = m.normals[i0] + m.normals[i1] + m.normals[i2];
    // CCW seen from outside: the winding agrees with the normals.
    EXPECT_GT(glm::dot(glm::cross(e1, e2), n), 0.0f) << "triangle " << t / 3;
    // glTF tangent frame: the tangent points along +u, and the bitangent
    // cross(normal, tangent) * w toward -v (up in the image, the normal map's +Y).
    const glm::vec2 d1 = m.uv0[i1] - m.uv0[i0], d2 = m.uv0[i2] - m.uv0[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    ASSERT_NE(det, 0.0f) << "triangle " << t / 3 << " has degenerate uvs";
    const glm::vec3 dpdu = (d2.y * e1 - d1.y * e2) / det;
    const glm::vec3 dpdv = (d1.x * e2 - d2.x * e1) / det;
    for (std::uint32_t i : {i0, i1, i2}) {
      const glm::vec4 tan = m.tangents[i];
      EXPECT_TRUE(tan.w == 1.0f || tan.w == -1.0f);
      EXPECT_NEAR(glm::dot(glm::vec3(tan), m.normals[i]), 0.0f, 1e-4f);
      EXPECT_GT(glm::dot(glm::vec3(tan), glm::normalize(dpdu)), 0.9f) << "vertex " << i;
      const glm::vec3 bitangent = glm::cross(m.normals[i], glm::vec3(tan)) * tan.w;
      EXPECT_LT(glm::dot(bitangent, glm::normalize(dpdv)), -0.9f) << "vertex " << i;
    }
  }
}

TEST(TexturedAsset, MaterialIsTexturedAndScattersUnderneath) {
  const Scene s = load_tile();
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& mat = s.materials[0];
  ASSERT_TRUE(mat.base_color_texture.has_value());
  ASSERT_LT(*mat.base_color_texture, s.textures.size());
  const Texture& base = s.textures[*mat.base_color_texture];
  ASSERT_NE(base.image, nullptr);
  EXPECT_EQ(base.image->width, 128u);
  EXPECT_EQ(base.image->height, 128u);
  EXPECT_EQ(base.image->pixels.size(), 128u * 128u * 4u);
  EXPECT_EQ(base.sampler.wrap_s, Wrap::Repeat);
  EXPECT_TRUE(base.sampler.mipmaps);
  // Not a flat colour: the checker has light and dark squares.
  int lo = 255, hi = 0;
  for (std::size_t p = 0; p < base.image->pixels.size(); p += 4) {
    lo = std::min<int>(lo, base.image->pixels[p + 1]);
    hi = std::max<int>(hi, base.image->pixels[p + 1]);
  }
  EXPECT_GT(hi - lo, 60);
  ASSERT_TRUE(mat.normal_texture.has_value());
  ASSERT_LT(*mat.normal_texture, s.textures.size());
  EXPECT_NE(*mat.normal_texture, *mat.base_color_texture);
  const Texture& normal = s.textures[*mat.normal_texture];
  ASSERT_NE(normal.image, nullptr);
  EXPECT_EQ(normal.image->width, 128u);
  // Mostly flat: the centre of a square points straight out (128, 128, 255).
  const std::size_t centre = (16u * 128u + 16u) * 4u;
  EXPECT_NEAR(normal.image->pixels[centre + 0], 128, 1);
  EXPECT_NEAR(normal.image->pixels[centre + 1], 128, 1);
  EXPECT_EQ(normal.image->pixels[centre + 2], 255);
  EXPECT_EQ(mat.metallic, 0.0f);

  ASSERT_TRUE(mat.sss.enabled);
  const auto* artist = std::get_if<ArtistSource>(&mat.sss.source);
  ASSERT_NE(artist, nullptr) << "extras.sss gives an artist colour and mean free path";
  EXPECT_EQ(mat.sss.model, profiles::kDefaultModel);  // no "model" given
  EXPECT_FALSE(mat.sss.medium.is_slab());
  // Cheap for the CPU reference: the SSS area is small next to mfp² × 1e5 (mm²).
  double area_mm2 = 0.0;
  for (const Instance& inst : s.instances) {
    const Mesh& mesh = s.meshes[inst.mesh];
    const auto world = [&](std::size_t i) {
      return glm::vec3(inst.world * glm::vec4(mesh.positions[mesh.indices[i]], 1.0f));
    };
    for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
      const glm::vec3 a = world(i), b = world(i + 1), c = world(i + 2);
      area_mm2 += 0.5 * glm::length(glm::cross(b - a, c - a)) * s.mm_per_unit * s.mm_per_unit;
    }
  }
  EXPECT_GT(area_mm2, 5000.0);
  EXPECT_LT(area_mm2, 7000.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(mat.sss.medium.sigma_a[c], 0.0);
    EXPECT_GT(mat.sss.medium.sigma_s[c], 0.0);
    const double mfp = mat.sss.effective_medium().channel(c).mfp_reduced();
    EXPECT_NEAR(mfp, artist->parameters.mfp_mm[c], 1e-6 * mfp);  // the mfp is 1/σt'
    EXPECT_LT(area_mm2, 0.1 * mfp * mfp * 1e5) << "channel " << c;
  }
}

TEST(TexturedAsset, HasItsOwnCameraAndLight) {
  const Scene s = load_tile();
  ASSERT_EQ(s.cameras.size(), 1u);
  ASSERT_EQ(s.lights.size(), 1u);
  const Camera& cam = s.cameras[0];
  EXPECT_EQ(cam.projection, Projection::Perspective);
  EXPECT_EQ(cam.aspect, 0.0f);  // takes the image's
  const Bounds b = s.bounds();
  // Above the tile, looking down at it, with the whole tile in a 16:9 frame.
  EXPECT_GT(cam.position().y, b.max.y);
  EXPECT_GT(glm::dot(cam.forward(), glm::normalize(b.center() - cam.position())), 0.99f);
  const glm::mat4 clip = clip_from_view(cam, 160, 90) * cam.view();
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                      (corner & 4) ? b.max.z : b.min.z);
    const glm::vec4 c = clip * glm::vec4(p, 1.0f);
    ASSERT_GT(c.w, 0.0f);
    EXPECT_LT(std::fabs(c.x / c.w), 1.0f) << "corner " << corner;
    EXPECT_LT(std::fabs(c.y / c.w), 1.0f) << "corner " << corner;
    EXPECT_GT(c.z / c.w, 0.0f);
    EXPECT_LT(c.z / c.w, 1.0f);
  }
  const Light& l = s.lights[0];
  EXPECT_EQ(l.type, LightType::Directional);
  EXPECT_FLOAT_EQ(l.intensity, 3.0f);
  EXPECT_EQ(l.color, glm::vec3(1.0f));
  EXPECT_FALSE(l.mask.has_value());
  EXPECT_LT(l.direction().y, -0.3f);  // from above: it lights the top
  EXPECT_LT(glm::dot(l.direction(), cam.forward()), 0.9f);  // not from the camera
}

}  // namespace
}  // namespace sss::scene
