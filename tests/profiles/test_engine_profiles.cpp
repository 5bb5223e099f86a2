// Engine profile exports (profiles/EngineProfiles.h): the Burley shape fit against
// Burley's own closed form, and each file's content against the material it came from.
#include "profiles/Burley.h"
#include "profiles/EngineProfiles.h"
#include "profiles/Presets.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

using namespace sss::profiles;

namespace {

// The numbers after "key: " on the line of `key` in a Unity YAML asset: "{r: 1, g: 2, ...}"
// gives 1, 2, ...; "5" gives 5.
std::vector<double> yaml_numbers(const std::string& yaml, const std::string& key) {
  const auto at = yaml.find("\n    " + key + ": ");
  if (at == std::string::npos) {
    ADD_FAILURE() << key << " missing in\n" << yaml;
    return {};
  }
  const std::string line = yaml.substr(at + 1, yaml.find('\n', at + 1) - at - 1);
  std::vector<double> out;
  const std::regex number(R"([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)");
  const std::string values = line.substr(line.find(':') + 1);
  for (std::sregex_iterator it(values.begin(), values.end(), number), end; it != end; ++it)
    out.push_back(std::stod(it->str()));
  return out;
}

Medium skin1() { return preset_medium(*find_preset("skin1")); }

}  // namespace

// A profile that IS Burley's shape gives Burley's own d back (Burley.h's closed form; the
// fit knows nothing of it) with no error: golden section to 1e-12 in ln d, so d within
// 1e-6 relative; the error is the trapezoid grid's alone, below 1e-6.
TEST(BurleyShapeFit, RecoversBurleysOwnDistance) {
  const Medium m = skin1();
  const RgbProfile profile(Model::Burley, m);
  const BurleyShapeFit fit = fit_burley_shape(profile);
  for (int c = 0; c < 3; ++c) {
    const double d = dynamic_cast<const Burley&>(profile.channel(c)).scale_d();
    EXPECT_NEAR(fit.d_mm[c], d, 1e-6 * d) << c;
    EXPECT_LT(fit.relative_error[c], 1e-6) << c;
  }
}

// For mc-table's skin1 the fit is a minimum of the error: 1% either side of d is worse
// (on a fine grid, n = 4000 intervals of ln r over the fit's range). The error the export
// reports is printed to 0.1% (sss-fit's "12.047%" to three decimals, the README's "12.0%"):
// it must equal the fine grid's to half of the README's last digit, 5e-4 absolute, so
// that the printed figure is the converged error and not the 160-sample grid's.
TEST(BurleyShapeFit, IsTheLeastSquaresMinimumForMcTable) {
  const RgbProfile profile(Model::McTable, skin1());
  const BurleyShapeFit fit = fit_burley_shape(profile);
  for (int c = 0; c < 3; ++c) {
    const auto error = [&](double d, int n) {
      double num = 0.0, den = 0.0;
      const double total = profile.total_reflectance()[c];
      const double lo = 1e-3 * profile.inner_radius(), hi = profile.support_radius();
      for (int i = 0; i <= n; ++i) {
        const double r = lo * std::pow(hi / lo, double(i) / n);
        const double w = r * std::log(hi / lo) / n * (i == 0 || i == n ? 0.5 : 1.0);
        const double t = r * profile.reflectance(r)[c] / total;
        const double b = (std::exp(-r / d) + std::exp(-r / (3 * d))) / (8 * M_PI * d);
        num += w * (t - b) * (t - b);
        den += w * t * t;
      }
      return std::sqrt(num / den);
    };
    const double d = fit.d_mm[c];
    const double e0 = error(d, 4000);
    EXPECT_LT(e0, error(1.01 * d, 4000)) << c;
    EXPECT_LT(e0, error(0.99 * d, 4000)) << c;
    EXPECT_NEAR(fit.relative_error[c], e0, 5e-4) << c;
    std::printf("[ Burley fit ] skin1 mc-table ch %d: d %.4f mm, relative L2 error %.3f%% "
                "(fine grid %.3f%%)\n", c, d, 100 * fit.relative_error[c], 100 * e0);
  }
}

TEST(HdrpDiffusionProfile, TheAssetHoldsTheFitAndTheMaterial) {
  EngineProfileSource s;
  s.name = "skin 1";
  s.medium = skin1();
  s.world_scale = 1.0;
  const RgbProfile profile(Model::McTable, s.medium);
  const HdrpDiffusionProfile p = hdrp_diffusion_profile(s, profile);
  const auto dist = yaml_numbers(p.asset, "scatteringDistance");
  const auto mult = yaml_numbers(p.asset, "scatteringDistanceMultiplier");
  ASSERT_EQ(dist.size(), 4u);
  ASSERT_EQ(mult.size(), 1u);
  double largest = 0.0;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(dist[c] * mult[0], p.fit.d_mm[c], 1e-8 * p.fit.d_mm[c]) << c;  // 9 digits
    largest = std::max(largest, dist[c]);
  }
  EXPECT_DOUBLE_EQ(largest, 1.0);  // an LDR colour, the length in the multiplier
  EXPECT_EQ(yaml_numbers(p.asset, "ior"), std::vector<double>{1.3});
  EXPECT_EQ(yaml_numbers(p.asset, "worldScale"), std::vector<double>{1.0});
  EXPECT_EQ(yaml_numbers(p.asset, "transmissionMode"), std::vector<double>{0.0});  // thick
  EXPECT_EQ(yaml_numbers(p.asset, "texturingMode"), std::vector<double>{1.0});     // post-scatter
  EXPECT_NE(p.asset.find("m_Name: skin_1\n"), std::string::npos) << p.asset;
  EXPECT_NE(p.asset.find("guid: b2686e09ec7aef44bad2843e4416f057, type: 3"), std::string::npos);
  EXPECT_NE(p.asset.find("--- !u!114 &11400000\nMonoBehaviour:"), std::string::npos);
  EXPECT_NE(p.asset.find("\n  m_Version: 2\n"), std::string::npos);
  EXPECT_TRUE(std::regex_search(p.meta, std::regex("\nguid: [0-9a-f]{32}\n")));
  EXPECT_NE(p.meta.find("mainObjectFileID: 11400000"), std::string::npos);
  // The same profile exports the same files (stable GUID); another name another GUID.
  EXPECT_EQ(hdrp_diffusion_profile(s, profile).meta, p.meta);
  s.name = "skin 2";
  EXPECT_NE(hdrp_diffusion_profile(s, profile).meta, p.meta);
  s.world_scale = 0.0001;
  EXPECT_THROW(hdrp_diffusion_profile(s, profile), std::invalid_argument);
}

// A slab: ThinObject, its thickness as the remap's end, and a tint with which HDRP's
// transmittance 0.25·tint·(e^{-t/d} + 3e^{-t/3d}) is the multipole's total transmittance.
TEST(HdrpDiffusionProfile, ASlabTransmitsTheProjectsColour) {
  EngineProfileSource s;
  s.name = "leaf";
  s.medium = skin1();
  s.medium.thickness_mm = 2.0;
  s.pre_post_albedo = true;
  const RgbProfile profile(Model::Multipole, s.medium);
  const HdrpDiffusionProfile p = hdrp_diffusion_profile(s, profile);
  EXPECT_EQ(yaml_numbers(p.asset, "transmissionMode"), std::vector<double>{1.0});
  EXPECT_EQ(yaml_numbers(p.asset, "texturingMode"), std::vector<double>{0.0});
  EXPECT_EQ(yaml_numbers(p.asset, "thicknessRemap"), (std::vector<double>{0.0, 2.0}));
  const auto tint = yaml_numbers(p.asset, "transmissionTint");
  ASSERT_EQ(tint.size(), 4u);
  for (int c = 0; c < 3; ++c) {
    const double d = p.fit.d_mm[c];
    const double hdrp = 0.25 * tint[c] * (std::exp(-2.0 / d) + 3.0 * std::exp(-2.0 / (3.0 * d)));
    EXPECT_NEAR(hdrp, profile.total_transmittance()[c], 1e-8 * profile.total_transmittance()[c]) << c;
  }
}

// Unreal: the JSON's mean free path is 1/σt in cm, the albedo the model's total, and the
// editor script is valid Python (compiled by python3; the README's test command installs it).
TEST(UnrealSubsurfaceProfile, TheJsonHoldsTheMaterialAndTheScriptCompiles) {
  EngineProfileSource s;
  s.name = "Marble";
  s.medium = preset_medium(*find_preset("marble"));
  s.world_scale = 0.1;
  const RgbProfile profile(Model::McTable, s.medium);
  const UnrealSubsurfaceProfile p = unreal_subsurface_profile(s, profile);
  const nlohmann::json j = nlohmann::json::parse(p.json);
  const double distance = j["MeanFreePathDistance"].get<double>();
  for (int c = 0; c < 3; ++c) {
    const double mfp_cm = 0.1 / (s.medium.sigma_a[c] + s.medium.sigma_s[c]);
    EXPECT_NEAR(j["MeanFreePathColor"][c].get<double>() * distance, mfp_cm, 1e-8 * mfp_cm) << c;
    EXPECT_NEAR(j["SurfaceAlbedo"][c].get<double>(), profile.total_reflectance()[c], 1e-8) << c;
    EXPECT_LE(j["MeanFreePathColor"][c].get<double>(), 1.0);
  }
  EXPECT_EQ(j["IOR"].get<double>(), 1.5);
  EXPECT_EQ(j["WorldUnitScale"].get<double>(), 0.1);
  EXPECT_TRUE(j["bEnableBurley"].get<bool>());
  EXPECT_EQ(j["name"], "Marble");
  EXPECT_NE(p.python.find("unreal.SubsurfaceProfile"), std::string::npos);
  const std::string key = "\"mean_free_path_distance\", ";
  const auto at = p.python.find(key);
  ASSERT_NE(at, std::string::npos) << p.python;
  EXPECT_NEAR(std::stod(p.python.substr(at + key.size())), distance, 1e-8 * distance);

  const auto dir = std::filesystem::temp_directory_path() / "sss_unreal_script";
  std::filesystem::create_directories(dir);
  const auto py = dir / "Marble.py";
  std::ofstream(py) << p.python;
  const std::string cmd = "python3 -c \"import sys; compile(open(sys.argv[1]).read(), sys.argv[1], 'exec')\" " +
                          py.string() + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << p.python;
  // A broken script is caught by the same check.
  std::ofstream(py) << p.python << "settings.set_editor_property(\n";
  EXPECT_NE(std::system(cmd.c_str()), 0);
  std::filesystem::remove_all(dir);
}

TEST(EngineProfiles, AssetNamesAreIdentifiers) {
  EXPECT_EQ(engine_asset_name("skin 1/a"), "skin_1_a");
  EXPECT_EQ(engine_asset_name("1st"), "SSS_1st");
  EXPECT_EQ(engine_asset_name(""), "SssProfile");
}
