// Debian's assimp-testmodels: every glTF file loads or returns a LoadError, never
// crashes (valid and deliberately broken files). Known cases are pinned.
#include "scene/GltfLoader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace sss::scene {
namespace {

const std::filesystem::path kModels = "/usr/share/assimp/models";

std::vector<std::filesystem::path> gltf_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string outcome(const std::filesystem::path& p) {
  auto r = load_gltf(p.string());
  if (auto* e = std::get_if<LoadError>(&r)) return "error: " + e->what();
  const Scene& s = std::get<Scene>(r);
  for (const Mesh& m : s.meshes) EXPECT_EQ(check_mesh(m), std::nullopt) << p << " " << m.name;
  return "ok: " + std::to_string(s.meshes.size()) + " meshes, " +
         std::to_string(s.triangle_count()) + " triangles";
}

TEST(AssimpCorpus, EveryGltf2FileLoadsOrFailsCleanly) {
  if (!std::filesystem::is_directory(kModels / "glTF2")) GTEST_SKIP() << "assimp-testmodels not installed";
  int ok = 0, failed = 0;
  for (const auto& p : gltf_files(kModels / "glTF2")) {
    const std::string o = outcome(p);
    (o.rfind("ok", 0) == 0 ? ok : failed)++;
    std::cout << "  " << p.lexically_relative(kModels).string() << ": " << o << "\n";
  }
  std::cout << "  glTF2: " << ok << " loaded, " << failed << " refused\n";
  EXPECT_GT(ok, 10);
}

TEST(AssimpCorpus, Gltf1FilesAreRefused) {
  if (!std::filesystem::is_directory(kModels / "glTF")) GTEST_SKIP() << "assimp-testmodels not installed";
  for (const auto& p : gltf_files(kModels / "glTF")) {
    auto r = load_gltf(p.string());
    EXPECT_TRUE(std::holds_alternative<LoadError>(r)) << p;
  }
}

TEST(AssimpCorpus, KnownFiles) {
  if (!std::filesystem::is_directory(kModels / "glTF2")) GTEST_SKIP() << "assimp-testmodels not installed";
  const auto load = [](const char* rel) { return load_gltf((kModels / "glTF2" / rel).string()); };
  for (const char* good : {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
                           "BoxTextured-glTF-Embedded/BoxTextured.gltf",
                           "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}) {
    auto r = load(good);
    ASSERT_TRUE(std::holds_alternative<Scene>(r)) << good << ": " << std::get<LoadError>(r).what();
  }
  const Scene box = std::get<Scene>(load("BoxTextured-glTF/BoxTextured.gltf"));
  ASSERT_EQ(box.textures.size(), 1u);
  EXPECT_GT(box.textures[0].image->width, 0u);
  const std::pair<const char*, const char*> bad[] = {
      {"IndexOutOfRange/IndexOutOfRange.gltf", "indices"},
      {"RecursiveNodes/RecursiveNodes.gltf", "nodes["},
      {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
  };
  for (const auto& [rel, needle] : bad) {
    auto r = load(rel);
    ASSERT_TRUE(std::holds_alternative<LoadError>(r)) << rel;
    EXPECT_NE(std::get<LoadError>(r).what().find(needle), std::string::npos)
        << std::get<LoadError>(r).what();
  }
}

// assimp's Draco-compressed 2CylinderEngine (KHR_draco_mesh_compression, written by
// Draco's own tools, not ours) loads as its uncompressed GLB: the same meshes, each with
// at most as many triangles (Draco's encoder drops degenerate ones: 792 of 936 in mesh
// 2), and every mesh's bounds within half a quantization step of the scene's extent at
// 8 bits, 0.5/255: Draco quantizes positions to 11 bits by default (draco_encoder -qp)
// and no tool's default is below 8.
TEST(AssimpCorpus, DracoFileLoadsAsTheUncompressedOne) {
  if (!std::filesystem::is_directory(kModels / "glTF2")) GTEST_SKIP() << "assimp-testmodels not installed";
  auto d = load_gltf((kModels / "glTF2" / "draco/2CylinderEngine.gltf").string());
  auto u = load_gltf((kModels / "glTF2" / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb").string());
  ASSERT_TRUE(std::holds_alternative<Scene>(d)) << std::get<LoadError>(d).what();
  ASSERT_TRUE(std::holds_alternative<Scene>(u)) << std::get<LoadError>(u).what();
  const Scene& a = std::get<Scene>(u);
  const Scene& b = std::get<Scene>(d);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  const Bounds box = a.bounds();
  const glm::vec3 e = box.max - box.min;
  const float tol = 0.5f / 255.0f * std::max({e.x, e.y, e.z});
  float worst = 0.0f;
  for (std::size_t m = 0; m < a.meshes.size(); ++m) {
    EXPECT_LE(b.meshes[m].indices.size(), a.meshes[m].indices.size()) << m;
    EXPECT_GT(b.meshes[m].indices.size(), 0u) << m;
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(a.meshes[m].bounds.min[c] - b.meshes[m].bounds.min[c]));
      worst = std::max(worst, std::abs(a.meshes[m].bounds.max[c] - b.meshes[m].bounds.max[c]));
    }
  }
  EXPECT_LE(worst, tol);
  std::printf("[ Draco 2CylinderEngine ] worst mesh bound difference %.3g of %.3g\n", worst, tol);
}

}  // namespace
}  // namespace sss::scene
