// Debian's assimp-testmodels: every glTF file loads or returns a LoadError, never
// crashes (valid and deliberately broken files). Known cases are pinned.
#include "renderer/scene/GltfLoader.h"

#include <gtest/gtest.h>

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
      {"draco/2CylinderEngine.gltf", "KHR_draco_mesh_compression"},
  };
  for (const auto& [rel, needle] : bad) {
    auto r = load(rel);
    ASSERT_TRUE(std::holds_alternative<LoadError>(r)) << rel;
    EXPECT_NE(std::get<LoadError>(r).what().find(needle), std::string::npos)
        << std::get<LoadError>(r).what();
  }
}

}  // namespace
}  // namespace sss::scene
