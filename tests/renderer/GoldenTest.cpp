// Golden frames of the built-in scenes: the display image (tonemapped, sRGB, 8-bit)
// compared with tests/golden/regression/NAME.png under the per-test tolerances of
// tests/golden/regression/tolerances.json. On failure the actual, expected and diff (x8) images are written
// next to the test binary (golden-out/) and named in the message. Bless with
// tests/golden/bless.sh after looking at the new images.
#include "RenderTest.h"

#include "scene/BuiltinScenes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#ifdef SSS_SOURCE_DIR

namespace sss::renderer::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(SSS_SOURCE_DIR) / "tests" / "golden" / "regression";

struct GoldenCase {
  const char* name;
  const char* scene;
  SssTechnique technique;
  std::uint32_t width, height;
};

const GoldenCase kCases[] = {
    {"sphere_off", "builtin:sphere", SssTechnique::Off, 160, 90},
    {"sphere_separable", "builtin:sphere", SssTechnique::Separable, 160, 90},
    {"sphere_gaussians", "builtin:sphere", SssTechnique::Gaussians, 160, 90},
    {"materials_separable", "builtin:materials", SssTechnique::Separable, 240, 135},
    {"bunny_separable", "builtin:bunny", SssTechnique::Separable, 160, 90},
    {"edge_gaussians", "builtin:edge", SssTechnique::Gaussians, 128, 16},
    // Texture space at 512^2 (the sphere's own UVs with their seam; the bunny's generated atlas).
    {"sphere_texture", "builtin:sphere", SssTechnique::Texture, 160, 90},
    {"bunny_texture", "builtin:bunny", SssTechnique::Texture, 160, 90},
};

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.name; }

int code(float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

class GoldenTest : public RenderTest, public ::testing::WithParamInterface<GoldenCase> {};

TEST_P(GoldenTest, DisplayImageMatchesTheGolden) {
  const GoldenCase& c = GetParam();
  auto loaded = scene::load_scene(c.scene);
  ASSERT_TRUE(std::holds_alternative<scene::Scene>(loaded)) << c.scene;
  RenderOptions options = small_options(c.width, c.height, c.technique);
  options.texture_size = 512;
  const Frame f = render(std::get<scene::Scene>(loaded), options);
  const fs::path golden = kGoldenDir / (std::string(c.name) + ".png");
  if (std::getenv("SSS_BLESS") != nullptr) {
    image::write_png(golden.string(), f.display);
    GTEST_SKIP() << "blessed " << golden;
  }
  std::ifstream tolerance_file(kGoldenDir / "tolerances.json");
  ASSERT_TRUE(tolerance_file) << "missing " << (kGoldenDir / "tolerances.json");
  const nlohmann::json tolerances = nlohmann::json::parse(tolerance_file);
  ASSERT_TRUE(tolerances.contains(c.name)) << "no tolerance for " << c.name;
  const nlohmann::json& tol = tolerances[c.name];
  const int max_code_diff = tol.at("max_code_diff").get<int>();
  const double max_failing = tol.at("max_failing_fraction").get<double>();
  const int hard_limit = tol.at("hard_limit").get<int>();

  auto expected_or = image::read_image(golden.string());
  ASSERT_TRUE(std::holds_alternative<image::Image>(expected_or))
      << "missing golden " << golden << ": run tests/golden/bless.sh";
  const image::Image& expected = std::get<image::Image>(expected_or);
  ASSERT_EQ(expected.width, f.display.width);
  ASSERT_EQ(expected.height, f.display.height);

  image::Image diff(expected.width, expected.height);
  int failing = 0, worst = 0;
  for (int y = 0; y < expected.height; ++y)
    for (int x = 0; x < expected.width; ++x) {
      int pixel_worst = 0;
      for (int ch = 0; ch < 3; ++ch) {
        const int d = std::abs(code(f.display.pixel(x, y)[ch]) - code(expected.pixel(x, y)[ch]));
        pixel_worst = std::max(pixel_worst, d);
        diff.pixel(x, y)[ch] = std::min(1.0f, 8.0f * float(d) / 255.0f);
      }
      diff.pixel(x, y)[3] = 1.0f;
      worst = std::max(worst, pixel_worst);
      if (pixel_worst > max_code_diff) ++failing;
    }
  const double fraction = double(failing) / double(expected.width * expected.height);
  const bool ok = fraction <= max_failing && worst <= hard_limit;
  if (!ok) {
    const fs::path out = fs::current_path() / "golden-out";
    fs::create_directories(out);
    image::write_png((out / (std::string(c.name) + ".actual.png")).string(), f.display);
    image::write_png((out / (std::string(c.name) + ".expected.png")).string(), expected);
    image::write_png((out / (std::string(c.name) + ".diff.png")).string(), diff);
    ADD_FAILURE() << c.name << ": " << failing << " pixels (" << fraction
                  << ") differ by more than " << max_code_diff << " codes (allowed "
                  << max_failing << "), worst " << worst << " (hard limit " << hard_limit
                  << "); actual/expected/diff written to " << out;
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, GoldenTest, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<GoldenCase>& param_info) {
                           return std::string(param_info.param.name);
                         });

}  // namespace
}  // namespace sss::renderer::testing

#endif  // SSS_SOURCE_DIR
