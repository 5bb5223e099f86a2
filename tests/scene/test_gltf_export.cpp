// gltf_with_sss_materials (the viewer's "export material"): the written copy loads back
// with the edited SSS materials and everything else unchanged; GLB keeps its BIN chunk;
// the input is never the target; relative URIs pin the copy to the input's folder.
#include "scene/GltfExport.h"
#include "scene/GltfLoader.h"

#include "GltfTestWriter.h"
#include "LoadExpect.h"
#include "SssExpect.h"

#include <gtest/gtest.h>

#include <fstream>

namespace sss::scene {
namespace {

using testing::GltfTestWriter;
using testing::TempDir;
using testing::expect_same_sss;
using testing::load_ok;

// One triangle, three materials: SSS coefficients, a plain surface with other extras,
// and a preset that is disabled.
GltfTestWriter three_materials() {
  GltfTestWriter w;
  const int pos = w.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  w.push("materials", {{"name", "skin"},
                       {"extras", {{"sss", {{"sigma_a", {0.01, 0.02, 0.03}}, {"sigma_s", 2.0}}}}}});
  w.push("materials", {{"name", "plain"}, {"extras", {{"author", "test"}}}});
  w.push("materials", {{"name", "off"}, {"extras", {{"sss", {{"preset", "skin2"}, {"enabled", false}}}}}});
  w.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"material", 0}}}}});
  w.push("nodes", {{"mesh", 0}});
  w.doc["scenes"] = {{{"nodes", {0}}}};
  return w;
}

void write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// The edit a user makes in the viewer: another model, an artist source, 3 Gaussians.
std::vector<Material> edited(const Scene& s) {
  std::vector<Material> m = s.materials;
  ArtistSource artist;
  artist.parameters.color = {0.5, 0.3, 0.2};
  artist.parameters.mfp_mm = {3.0, 1.5, 0.75};
  auto made = make_sss_material(artist, profiles::Model::Burley, 3, 2.0, AlbedoMode::PrePost);
  EXPECT_EQ(made.index(), 0u);
  m[0].sss = std::get<SssMaterial>(made);
  return m;
}

void check_round_trip(const std::filesystem::path& input, const std::filesystem::path& output) {
  const Scene before = load_ok(input);
  ASSERT_EQ(before.materials.size(), 3u);
  const std::vector<Material> materials = edited(before);
  auto bytes = gltf_with_sss_materials(input.string(), materials, output.string());
  ASSERT_EQ(bytes.index(), 0u) << std::get<LoadError>(bytes).what();
  write(output, std::get<std::string>(bytes));
  const Scene after = load_ok(output);
  ASSERT_EQ(after.materials.size(), 3u);
  expect_same_sss(after.materials[0].sss, materials[0].sss);
  EXPECT_FALSE(after.materials[1].sss.enabled);
  EXPECT_FALSE(after.materials[2].sss.enabled);  // still there, still off
  EXPECT_EQ(after.materials[2].name, "off");
  ASSERT_EQ(after.meshes.size(), before.meshes.size());
  EXPECT_EQ(after.meshes[0].positions, before.meshes[0].positions);
}

TEST(GltfExport, GltfCopyLoadsBackWithTheEditedMaterial) {
  const TempDir dir("export_gltf");
  three_materials().write_gltf(dir / "a.gltf");
  check_round_trip(dir / "a.gltf", dir / "a-sss.gltf");
  // Other extras keys stay.
  std::ifstream in(dir / "a-sss.gltf");
  const auto doc = nlohmann::json::parse(in);
  EXPECT_EQ(doc["materials"][1]["extras"]["author"], "test");
  EXPECT_FALSE(doc["materials"][1]["extras"].contains("sss"));
}

TEST(GltfExport, GlbCopyKeepsItsBinaryChunk) {
  const TempDir dir("export_glb");
  three_materials().write_glb(dir / "a.glb");
  check_round_trip(dir / "a.glb", dir / "b.glb");
}

TEST(GltfExport, ExternalBufferPinsTheCopyToTheInputsFolder) {
  const TempDir dir("export_external");
  three_materials().write_gltf_external(dir / "a.gltf", "a.bin");
  check_round_trip(dir / "a.gltf", dir / "a-sss.gltf");
  std::filesystem::create_directories(dir / "elsewhere");
  const Scene s = load_ok(dir / "a.gltf");
  auto r = gltf_with_sss_materials((dir / "a.gltf").string(), s.materials,
                                   (dir / "elsewhere" / "a.gltf").string());
  ASSERT_EQ(r.index(), 1u);
  const std::string e = std::get<LoadError>(r).what();
  EXPECT_NE(e.find("a.gltf"), std::string::npos) << e;
  EXPECT_NE(e.find("same folder"), std::string::npos) << e;
}

TEST(GltfExport, NeverTheInputItself) {
  const TempDir dir("export_self");
  three_materials().write_gltf(dir / "a.gltf");
  const Scene s = load_ok(dir / "a.gltf");
  for (const std::string& target : {(dir / "a.gltf").string(), (dir / "." / "a.gltf").string()}) {
    auto r = gltf_with_sss_materials((dir / "a.gltf").string(), s.materials, target);
    ASSERT_EQ(r.index(), 1u) << target;
    EXPECT_NE(std::get<LoadError>(r).what().find("overwrite"), std::string::npos);
  }
}

TEST(GltfExport, MissingOrBrokenInputNamesTheFile) {
  const TempDir dir("export_bad");
  auto missing = gltf_with_sss_materials((dir / "none.gltf").string(), {}, (dir / "o.gltf").string());
  ASSERT_EQ(missing.index(), 1u);
  EXPECT_NE(std::get<LoadError>(missing).what().find("none.gltf"), std::string::npos);
  write(dir / "bad.gltf", "{ not json");
  auto bad = gltf_with_sss_materials((dir / "bad.gltf").string(), {}, (dir / "o.gltf").string());
  ASSERT_EQ(bad.index(), 1u);
  EXPECT_NE(std::get<LoadError>(bad).what().find("bad.gltf"), std::string::npos);
}

TEST(GltfExport, UnusedPathCountsUp) {
  const TempDir dir("export_names");
  EXPECT_EQ(default_export_path((dir / "a.glb").string()), (dir / "a-sss.glb").string());
  write(dir / "a-sss.glb", "x");
  EXPECT_EQ(default_export_path((dir / "a.glb").string()), (dir / "a-sss-2.glb").string());
  write(dir / "a-sss-2.glb", "x");
  EXPECT_EQ(unused_path((dir / "a-sss.glb").string()), (dir / "a-sss-3.glb").string());
}

}  // namespace
}  // namespace sss::scene
