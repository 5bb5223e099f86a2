// The loader's guards, unit by unit: GLB container, URIs, base64, the file sandbox, JSON
// depth, and the size caps of LoadOptions.
#include "scene/GltfFile.h"
#include "scene/GltfJson.h"
#include "scene/GltfLoader.h"
#include "scene/GltfUri.h"

#include "GltfTestWriter.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace sss::scene {
namespace {

std::vector<unsigned char> glb(std::uint32_t json_len, std::uint32_t total, std::size_t real) {
  std::vector<unsigned char> b(std::max<std::size_t>(real, 24), ' ');
  const auto put = [&](std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b[at + std::size_t(i)] = static_cast<unsigned char>(v >> (8 * i));
  };
  b[0] = 'g', b[1] = 'l', b[2] = 'T', b[3] = 'F';
  put(4, 2);
  put(8, total);
  put(12, json_len);
  put(16, 0x4E4F534Au);
  b[20] = '{';
  if (b.size() > 21) b[21] = '}';
  b.resize(real);  // a truncated file keeps only its first bytes
  return b;
}

TEST(GlbContainer, Layout) {
  const auto bytes28 = glb(8, 28, 28);  // the layout views into these bytes
  auto ok = parse_glb(bytes28);
  ASSERT_TRUE(std::holds_alternative<GlbLayout>(ok));
  EXPECT_EQ(std::get<GlbLayout>(ok).json, "{}");  // padding removed
  EXPECT_TRUE(std::get<GlbLayout>(ok).bin.empty());
  const std::pair<std::vector<unsigned char>, const char*> bad[] = {
      {glb(8, 28, 11), "header"},
      {glb(8, 28, 27), "header.length"},
      {glb(0xFFFFFFF8u, 28, 28), "chunks[0].chunkLength"},
      {glb(6, 26, 26), "chunks[0].chunkLength"},  // not a multiple of 4
      {glb(4, 28, 28), "chunks[1]"},              // 4 bytes left: no room for a header
      {glb(0, 20, 20), "chunks[0].chunkLength"},
  };
  auto padding_only = glb(8, 28, 28);
  padding_only[20] = padding_only[21] = ' ';
  auto r0 = parse_glb(padding_only);
  ASSERT_TRUE(std::holds_alternative<FieldError>(r0));
  EXPECT_NE(std::get<FieldError>(r0).message.find("only padding"), std::string::npos);
  // rebuild_glb gives a canonical file that parses to the same layout.
  const auto rebuilt = rebuild_glb(std::get<GlbLayout>(ok));
  EXPECT_EQ(rebuilt.size(), 24u);
  auto again = parse_glb(rebuilt);
  ASSERT_TRUE(std::holds_alternative<GlbLayout>(again));
  EXPECT_EQ(std::get<GlbLayout>(again).json, "{}");
  for (const auto& [bytes, field] : bad) {
    auto r = parse_glb(bytes);
    ASSERT_TRUE(std::holds_alternative<FieldError>(r)) << field;
    EXPECT_EQ(std::get<FieldError>(r).field, field) << std::get<FieldError>(r).what();
  }
}

TEST(Uris, Accepted) {
  EXPECT_EQ(check_uri("mesh.bin", UriUse::Buffer), std::nullopt);
  EXPECT_EQ(check_uri("sub/dir/mesh%20a.bin", UriUse::Buffer), std::nullopt);
  EXPECT_EQ(check_uri("./a..b/c.png", UriUse::Image), std::nullopt);
  EXPECT_EQ(check_uri("data:application/octet-stream;base64,AAECAw==", UriUse::Buffer, 4), std::nullopt);
  EXPECT_EQ(check_uri("data:application/gltf-buffer;base64,AAEC", UriUse::Buffer, 3), std::nullopt);
  EXPECT_EQ(check_uri("data:image/jpeg;base64,AAEC", UriUse::Image), std::nullopt);
}

TEST(Uris, Refused) {
  const std::pair<const char*, const char*> cases[] = {
      {"", "empty"},
      {"/etc/passwd", "absolute"},
      {"../x.bin", "\"..\""},
      {"a/../../x.bin", "\"..\""},
      {"a/..", "\"..\""},
      {"%2E%2E/x.bin", "percent-decoded"},
      {"%2fetc/passwd", "absolute path once percent-decoded"},
      {"x%00.bin", "control character once"},
      {"x%zz.bin", "percent-escape"},
      {"x%2", "percent-escape"},
      {"a\\b.bin", "backslash"},
      {"C:/x.bin", "scheme"},
      {"https://example.com/x.bin", "scheme"},
      {"file:///etc/passwd", "scheme"},
      {"DATA:application/octet-stream;base64,AAAA", "scheme"},
      {"data:application/octet-stream,AAAA", "not base64"},
      {"data:application/octet-stream;base64", "without a ','"},
      {"data:text/html;base64,AAAA", "text/html"},
      {"data:image/png;base64,AAAA", "image/png"},  // as a buffer
      {"data:application/octet-stream;base64,AAA", "base64"},
      {"data:application/octet-stream;base64,A=AA", "base64"},
      {"data:application/octet-stream;base64,====", "base64"},
      {"data:application/octet-stream;base64,AA AA", "base64"},
      {"data:application/octet-stream;base64,", "base64"},
  };
  for (const auto& [uri, phrase] : cases) {
    const auto e = check_uri(uri, UriUse::Buffer);
    ASSERT_TRUE(e.has_value()) << uri;
    EXPECT_NE(e->find(phrase), std::string::npos) << uri << ": " << *e;
  }
  EXPECT_NE(check_uri("data:application/octet-stream;base64,AAECAw==", UriUse::Buffer, 5), std::nullopt);
  EXPECT_NE(check_uri("data:application/octet-stream;base64,AAAA", UriUse::Image), std::nullopt);
}

TEST(Uris, Base64Size) {
  EXPECT_EQ(base64_decoded_size("AAAA"), 3u);
  EXPECT_EQ(base64_decoded_size("AAA="), 2u);
  EXPECT_EQ(base64_decoded_size("AA=="), 1u);
  EXPECT_EQ(base64_decoded_size("A==="), std::nullopt);
  EXPECT_EQ(base64_decoded_size("AA=A"), std::nullopt);
}

TEST(Sandbox, ContainsOnlyTheFolder) {
  FileSandbox box;
  box.root = "/data/scene";
  EXPECT_TRUE(box.contains("/data/scene/a.bin"));
  EXPECT_TRUE(box.contains("/data/scene/sub/./a.bin"));
  EXPECT_FALSE(box.contains("/data/scene"));
  EXPECT_FALSE(box.contains("/data/scene/../secret"));
  EXPECT_FALSE(box.contains("/data/scenery/a.bin"));
  EXPECT_FALSE(box.contains("./a.bin"));
  EXPECT_FALSE(box.contains("/etc/passwd"));
}

// A symbolic link inside the folder that points out of it is refused like "../x": the
// path is checked again after links are resolved.
TEST(Sandbox, LinksOutOfTheFolderAreRefused) {
  const testing::TempDir dir("sandbox_link");
  std::filesystem::create_directories(dir / "scene");
  testing::GltfTestWriter w;
  const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const int p = w.floats(pos, "VEC3", 3);
  w.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", p}}}}}}});
  w.push("nodes", {{"mesh", 0}});
  // The real .bin lies outside the scene folder; scene/tri.bin links to it.
  w.write_gltf_external(dir / "outside.gltf", "tri.bin");
  std::filesystem::create_symlink(dir / "tri.bin", dir / "scene/tri.bin");
  std::filesystem::copy_file(dir / "outside.gltf", dir / "scene/linked.gltf");
  ASSERT_TRUE(std::holds_alternative<Scene>(load_gltf((dir / "outside.gltf").string())));
  auto r = load_gltf((dir / "scene/linked.gltf").string());
  ASSERT_TRUE(std::holds_alternative<LoadError>(r));
  EXPECT_NE(std::get<LoadError>(r).what().find("tri.bin"), std::string::npos) << std::get<LoadError>(r).what();
  // A link that stays inside the folder is fine.
  std::filesystem::rename(dir / "tri.bin", dir / "scene/real.bin");
  std::filesystem::remove(dir / "scene/tri.bin");
  std::filesystem::create_symlink("real.bin", dir / "scene/tri.bin");
  r = load_gltf((dir / "scene/linked.gltf").string());
  EXPECT_TRUE(std::holds_alternative<Scene>(r)) << std::get<LoadError>(r).what();
}

TEST(Images, MediaTypeFromSignature) {
  const std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  const std::vector<unsigned char> jpeg = {0xFF, 0xD8, 0xFF, 0xE0};
  const std::vector<unsigned char> gif = {'G', 'I', 'F', '8', '9', 'a'};
  EXPECT_EQ(image_media_type(png), "image/png");
  EXPECT_EQ(image_media_type(jpeg), "image/jpeg");
  EXPECT_EQ(image_media_type(gif), "");
  EXPECT_EQ(image_media_type(std::span<const unsigned char>(png).first(7)), "");
}

TEST(JsonDepth, CountsOutsideStrings) {
  EXPECT_EQ(check_json_depth(R"({"a": [[["]]]]]]]]"]]]})", 4), std::nullopt);
  EXPECT_NE(check_json_depth("[[[[[", 4), std::nullopt);
  EXPECT_EQ(check_json_depth(R"({"a\"[[[[[": 1})", 1), std::nullopt);
  // Past a NUL the parser reads nothing (fuzz/regressions/sss_extras/nul_then_deep_garbage):
  // the depth there does not count, so the text and JSON entry points agree.
  EXPECT_EQ(check_json_depth(std::string_view("[1]\0[[[[[[[[", 12), 4), std::nullopt);
  EXPECT_NE(check_json_depth(std::string_view("[[[[[\0", 6), 4), std::nullopt);
}

TEST(LoadOptions, CapsAreEnforced) {
  const testing::TempDir dir("caps");
  testing::GltfTestWriter w;
  std::vector<float> pos;
  for (int i = 0; i < 3000; ++i) pos.insert(pos.end(), {float(i), 0, 0, float(i), 1, 0, float(i), 0, 1});
  const int p = w.floats(pos, "VEC3", 3);
  w.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", p}}}}}}});
  w.push("nodes", {{"mesh", 0}});
  w.write_gltf(dir / "big.gltf");
  LoadOptions small;
  small.max_scene_bytes = 50000;
  auto r = load_gltf((dir / "big.gltf").string(), small);
  ASSERT_TRUE(std::holds_alternative<LoadError>(r));
  EXPECT_NE(std::get<LoadError>(r).what().find("max_scene_bytes"), std::string::npos)
      << std::get<LoadError>(r).what();
  EXPECT_TRUE(std::holds_alternative<Scene>(load_gltf((dir / "big.gltf").string())));
  LoadOptions few_nodes;
  few_nodes.max_nodes = 0;
  r = load_gltf((dir / "big.gltf").string(), few_nodes);
  ASSERT_TRUE(std::holds_alternative<LoadError>(r));
  EXPECT_EQ(std::get<LoadError>(r).object, "nodes");
}

TEST(LoadOptions, ImageSizeCap) {
  ImageLimits limits;
  limits.max_side = 1;
  // A 2x1 PNG (signature, IHDR) is refused from its header alone.
  const std::vector<unsigned char> png = {
      0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
      0, 0, 0, 2, 0, 0, 0, 1, 8, 2, 0, 0, 0, 0x00, 0x00, 0x00, 0x00};
  auto r = decode_image(png, limits);
  ASSERT_TRUE(std::holds_alternative<std::string>(r));
  EXPECT_NE(std::get<std::string>(r).find("larger than the limit"), std::string::npos)
      << std::get<std::string>(r);
  EXPECT_TRUE(std::holds_alternative<std::string>(decode_image({}, {})));
}

}  // namespace
}  // namespace sss::scene
