// Files written by tools not ours render as the originals (issue 21): Debian's gltfpack
// quantizes assets/bunny.glb and assets/textured_tile.glb (KHR_mesh_quantization, the UV
// range in KHR_texture_transform, vertices reordered) and compresses them with meshopt;
// glTF-Transform (npm, tools/node/variants.mjs) compresses the bunny with Draco and with
// meshopt's filters. Each file, rendered headless on lavapipe with the validation layer
// on, matches the original's frame.
#include <gtest/gtest.h>

#include "ViewerRun.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace sss::testing {
namespace {

#if defined(SSS_VIEWER_EXE) && defined(SSS_COMPARE_EXE)

// The tolerance of each variant comes from its normals, the only change a pixel at
// 320×180 can see: positions (14 bits: 3e-5 of the extent) and UVs (12 bits of their
// range: under a texel of the tile's 16 repeats of its texture) move nothing visibly. A
// normal moved by |Δn| changes a Lambert term n·l by at most |Δn|; at a mean n·l of 0.5
// that is 2|Δn| of the shading:
// - gltfpack's 8-bit normals: |Δn| <= √3 · 0.5/127 = 0.0068, tolerance 0.014;
// - octahedral 8-bit normals stored again in 8 bits (gltfpack -cc, glTF-Transform's
//   meshopt filter): |Δn| <= 0.0235 (test_quantized_gltf.cpp, octahedral_bound), 0.047;
// - Draco's 10-bit octahedral normals: |Δn| <= 0.0042, 0.0084.
struct Variant {
  const char* name;
  const char* asset;
  const char* command;  // IN and OUT are replaced by the paths
  double tolerance;
};
constexpr Variant kVariants[] = {
    {"gltfpack", "bunny", "gltfpack -ke -i IN -o OUT", 0.014},
    {"gltfpack", "textured_tile", "gltfpack -ke -i IN -o OUT", 0.014},
    {"gltfpack -cc (meshopt)", "bunny", "gltfpack -ke -cc -i IN -o OUT", 0.047},
    {"glTF-Transform meshopt filter", "bunny", "node " SSS_SOURCE_DIR "/tools/node/variants.mjs IN OUT meshopt-filter", 0.047},
    {"glTF-Transform Draco", "bunny", "node " SSS_SOURCE_DIR "/tools/node/variants.mjs IN OUT draco", 0.0084},
};

std::string replaced(std::string command, const std::string& in, const std::string& out) {
  command.replace(command.find("IN"), 2, "'" + in + "'");
  command.replace(command.find("OUT"), 3, "'" + out + "'");
  return command;
}

TEST(GltfpackRender, PackedFilesRenderTheOriginalsFrame) {
  for (std::size_t k = 0; k < std::size(kVariants); ++k) {
    const Variant& variant = kVariants[k];
    SCOPED_TRACE(std::string(variant.name) + " " + variant.asset);
    const std::string in = std::string(SSS_SOURCE_DIR) + "/assets/" + variant.asset + ".glb";
    const std::string tag = std::string(variant.asset) + "_" + std::to_string(k);
    const std::string packed = viewer_temp_path("gltfpack_render", tag + "_packed.glb");
    const std::string a = viewer_temp_path("gltfpack_render", tag + "_original.exr");
    const std::string b = viewer_temp_path("gltfpack_render", tag + "_packed.exr");
    const CliRun pack = run_shell(replaced(variant.command, in, packed) + " 2>&1");
    ASSERT_EQ(pack.code, 0) << pack.out;
    for (const auto& [file, out] : {std::pair{in, a}, std::pair{packed, b}}) {
      const CliRun v = run_shell("SSS_VALIDATION=1 env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(SSS_VIEWER_EXE) +
                                 " '" + file + "' --headless --width 320 --height 180 --out " + out);
      ASSERT_EQ(v.code, 0) << v.out;
      EXPECT_FALSE(has_validation_message(v.out)) << v.out;
    }
    const CliRun c = run_shell(std::string(SSS_COMPARE_EXE) + " " + b + " " + a + " --json");
    const auto doc = nlohmann::json::parse(c.out, nullptr, false);
    ASSERT_FALSE(doc.is_discarded()) << c.out;
    const double e = doc["metrics"]["relative_rmse"].get<double>();
    EXPECT_GT(e, 0.0);  // a real comparison: the packed file is not the original
    EXPECT_LE(e, variant.tolerance);
    std::printf("[ packed render ] %s, %s: relative RMSE %.4f (tolerance %.4f)\n", variant.name, variant.asset, e,
                variant.tolerance);
    for (const auto& p : {packed, a, b}) std::filesystem::remove(p);
  }
}

#endif

}  // namespace
}  // namespace sss::testing
