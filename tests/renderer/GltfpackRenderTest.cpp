// Files written by a tool not ours render as the originals (issue 21): Debian's gltfpack
// quantizes assets/bunny.glb and assets/textured_tile.glb (KHR_mesh_quantization, the UV
// range in KHR_texture_transform, vertices reordered); each packed file, rendered headless
// on lavapipe with the validation layer on, matches the original's frame.
#include <gtest/gtest.h>

#include "ViewerRun.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace sss::testing {
namespace {

#if defined(SSS_VIEWER_EXE) && defined(SSS_COMPARE_EXE)

// The tolerance: gltfpack keeps normals in 8 bits per component, a direction error of at
// most √3 · 0.5/127 = 0.0068 rad, which moves a Lambert term n·l by at most 0.0068; at a
// mean n·l of 0.5 that is 1.4% of the shading. Positions (14 bits: 3e-5 of the extent,
// far below a pixel at 320×180) and UVs (12 bits of their range: under a texel of the
// tile's 16 repeats of its texture) add no visible change.
constexpr double kTolerance = 0.014;

TEST(GltfpackRender, PackedFilesRenderTheOriginalsFrame) {
  for (const char* asset : {"bunny", "textured_tile"}) {
    SCOPED_TRACE(asset);
    const std::string in = std::string(SSS_SOURCE_DIR) + "/assets/" + asset + ".glb";
    const std::string packed = viewer_temp_path("gltfpack_render", std::string(asset) + "_packed.glb");
    const std::string a = viewer_temp_path("gltfpack_render", std::string(asset) + "_original.exr");
    const std::string b = viewer_temp_path("gltfpack_render", std::string(asset) + "_packed.exr");
    const CliRun pack = run_shell("gltfpack -ke -i '" + in + "' -o '" + packed + "' 2>&1");
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
    EXPECT_LE(e, kTolerance);
    std::printf("[ gltfpack render ] %s: relative RMSE %.4f (tolerance %.3f)\n", asset, e, kTolerance);
    for (const auto& p : {packed, a, b}) std::filesystem::remove(p);
  }
}

#endif

}  // namespace
}  // namespace sss::testing
