// --sss-material, --scale and the MEDIUM flags on a glTF that has no extras.sss (issue 20
// part 1), and the scatter-scale warnings (scene/ScatterScale.h). No GPU: the
// overrides and the checks are what sss-viewer and sss-reference run before rendering.
#include <gtest/gtest.h>

#include "app/common/MaterialOverrides.h"
#include "profiles/Presets.h"
#include "scene/BuiltinScenes.h"
#include "scene/GltfExport.h"
#include "scene/ScatterScale.h"
#include "common/TwoBoxesGltf.h"
#include "scene/GltfTestWriter.h"

#include <cmath>

namespace sss {
namespace {

using sss::testing::write_two_boxes;
using scene::testing::TempDir;

scene::Scene load(const std::filesystem::path& path) {
  auto loaded = scene::load_scene(path.string());
  EXPECT_TRUE(std::holds_alternative<scene::Scene>(loaded))
      << std::get<scene::LoadError>(loaded).what();
  scene::Scene s = std::get<scene::Scene>(std::move(loaded));
  scene::add_camera_if_missing(s);
  return s;
}

std::variant<int, FieldError> apply(scene::Scene& s, app::MaterialOverrideArgs a) {
  return app::apply_material_overrides(s, a);
}

std::string error_of(const std::variant<int, FieldError>& r) {
  const auto* e = std::get_if<FieldError>(&r);
  return e ? e->what() : std::string();
}

TEST(SssMaterialOption, EnablesAPlainGltfMaterialByNameIndexOrAll) {
  TempDir dir("sss_material_enable");
  const auto file = dir.path() / "boxes.glb";
  write_two_boxes(file, 0.05f);
  {
    scene::Scene s = load(file);
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_FALSE(s.materials[0].sss.enabled);
    EXPECT_TRUE(s.meshes[0].uv_atlas.empty());
    app::MaterialOverrideArgs a;
    a.sss_material = {"plastic=marble"};
    const auto r = apply(s, a);
    ASSERT_EQ(error_of(r), "");
    EXPECT_EQ(std::get<int>(r), 1);
    const scene::SssMaterial& m = s.materials[0].sss;
    ASSERT_TRUE(m.enabled);
    ASSERT_TRUE(std::holds_alternative<scene::PresetSource>(m.source));  // Export writes "preset"
    EXPECT_EQ(std::get<scene::PresetSource>(m.source).name, "marble");
    EXPECT_EQ(m.model, profiles::kDefaultModel);
    EXPECT_EQ(m.gaussians, scene::kDefaultGaussians);
    EXPECT_EQ(m.scale, 1.0);
    const profiles::Medium marble = profiles::preset_medium(*profiles::find_preset("marble"));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(m.medium.sigma_a[c], marble.sigma_a[c]);
    EXPECT_FALSE(s.materials[1].sss.enabled);
    // No atlas here: texture space builds the ones it needs (GpuScene::ensure_sss_uvs).
    EXPECT_TRUE(s.meshes[0].uv_atlas.empty());
    EXPECT_TRUE(s.meshes[1].uv_atlas.empty());
  }
  {  // By index, artist values, the spec's keys winning over the global options.
    scene::Scene s = load(file);
    app::MaterialOverrideArgs a;
    a.sss_material = {"1=color=0.8,0.5,0.4;mfp=2,1,0.5;scale=0.5;gaussians=2"};
    a.gaussians = 4;
    a.model = "dipole";
    ASSERT_EQ(error_of(apply(s, a)), "");
    const scene::SssMaterial& m = s.materials[1].sss;
    ASSERT_TRUE(m.enabled);
    ASSERT_TRUE(std::holds_alternative<scene::ArtistSource>(m.source));
    EXPECT_EQ(std::get<scene::ArtistSource>(m.source).parameters.mfp_mm[2], 0.5);
    EXPECT_EQ(m.model, profiles::Model::Dipole);  // global, the spec named none
    EXPECT_EQ(m.gaussians, 2);                    // the spec's
    EXPECT_EQ(m.scale, 0.5);
    // "metal" keeps metallic 1, which hides subsurface light: the user is told.
    bool warned = false;
    for (const std::string& w : s.warnings) warned = warned || w.find("'metal' is metallic") != std::string::npos;
    EXPECT_TRUE(warned);
  }
  {  // all, then off for one; coefficients.
    scene::Scene s = load(file);
    app::MaterialOverrideArgs a;
    a.sss_material = {"all=sigma-a=0.01,0.02,0.03;sigma-s=1,1.5,2;eta=1.4", "metal=off"};
    ASSERT_EQ(error_of(apply(s, a)), "");
    EXPECT_TRUE(s.materials[0].sss.enabled);
    EXPECT_TRUE(std::holds_alternative<scene::CoefficientSource>(s.materials[0].sss.source));
    EXPECT_EQ(s.materials[0].sss.medium.eta[1], 1.4);
    EXPECT_FALSE(s.materials[1].sss.enabled);
  }
}

// OpenPBR's keys in --sss-material keep the material's source OpenPBR (the panel shows
// its fields, Export writes extras.sss.openpbr); Standard Surface's radius colour likewise.
TEST(SssMaterialOption, OpenPbrAndStandardSurfaceKeysKeepTheirSource) {
  TempDir dir("sss_material_openpbr");
  const auto file = dir.path() / "boxes.glb";
  write_two_boxes(file, 0.05f);
  scene::Scene s = load(file);
  app::MaterialOverrideArgs a;
  a.sss_material = {"plastic=subsurface-color=0.6,0.4,0.3;subsurface-radius=2;eta=1.4;albedo-inversion=model",
                    "metal=subsurface-color=0.6,0.4,0.3;subsurface-radius=2,1,0.5;subsurface-scale=1"};
  ASSERT_EQ(error_of(apply(s, a)), "");
  const auto* p = std::get_if<scene::OpenPbrSource>(&s.materials[0].sss.source);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->inversion, profiles::AlbedoInversion::Model);
  EXPECT_FALSE(p->standard_surface);
  EXPECT_EQ(p->parameters.radius_mm, 2.0);
  EXPECT_EQ(p->parameters.ior, 1.4);
  const auto* ss = std::get_if<scene::OpenPbrSource>(&s.materials[1].sss.source);
  ASSERT_NE(ss, nullptr);
  EXPECT_TRUE(ss->standard_surface);
  EXPECT_EQ(ss->inversion, profiles::AlbedoInversion::VanDeHulst);
  // radius 2,1,0.5 × scale 1 against OpenPBR's 2 × (1, 0.5, 0.25): the same mean free paths.
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(s.materials[1].sss.medium.sigma_a[c] + s.materials[1].sss.medium.sigma_s[c],
                1.0 / (2.0 * std::pow(0.5, c)), 1e-12) << c;
  scene::Scene t = load(file);
  a.sss_material = {"plastic=subsurface-color=0.6;subsurface-radius=2;albedo-inversion=best"};
  EXPECT_NE(error_of(apply(t, a)).find("albedo-inversion"), std::string::npos);
  EXPECT_FALSE(t.materials[0].sss.enabled);
}

TEST(SssMaterialOption, ExportWritesWhatWasEnabled) {
  TempDir dir("sss_material_export");
  const auto file = dir.path() / "boxes.glb";
  write_two_boxes(file, 0.05f);
  scene::Scene s = load(file);
  app::MaterialOverrideArgs a;
  a.sss_material = {"plastic=marble;scale=0.5"};
  ASSERT_EQ(error_of(apply(s, a)), "");
  const auto out = dir.path() / "boxes-sss.glb";
  auto bytes = scene::gltf_with_sss_materials(file.string(), s.materials, out.string());
  ASSERT_TRUE(std::holds_alternative<std::string>(bytes)) << std::get<scene::LoadError>(bytes).what();
  {
    std::ofstream f(out, std::ios::binary);
    f << std::get<std::string>(bytes);
  }
  scene::Scene back = load(out);
  ASSERT_TRUE(back.materials[0].sss.enabled);
  ASSERT_TRUE(std::holds_alternative<scene::PresetSource>(back.materials[0].sss.source));
  EXPECT_EQ(std::get<scene::PresetSource>(back.materials[0].sss.source).name, "marble");
  EXPECT_EQ(back.materials[0].sss.scale, 0.5);
  EXPECT_FALSE(back.materials[1].sss.enabled);
}

TEST(SssMaterialOption, ErrorsNameWhatIsThereAndChangeNothing) {
  TempDir dir("sss_material_errors");
  const auto file = dir.path() / "boxes.glb";
  write_two_boxes(file, 0.05f);
  struct Case {
    std::vector<std::string> specs;
    std::string preset, scale_text;
    std::string expected;
  };
  const Case cases[] = {
      // A MEDIUM flag on a file without SSS was a silent no-op (issue 20).
      {{}, "marble", "", "--preset: matches no material"},
      {{"skin=marble"}, "", "", "no material named or numbered 'skin'; the scene's materials: 0 'plastic', 1 'metal'"},
      {{"7=marble"}, "", "", "no material named or numbered '7'"},
      {{"plastic"}, "", "", "expected TARGET=SPEC"},
      {{"plastic=marble;colour=0.5"}, "", "", "colour: unknown key"},
      {{"plastic=preset=marble;preset=skin1"}, "", "", "preset: given twice"},
      {{"plastic=scale=2"}, "", "", "has no subsurface medium yet"},
      {{"plastic=marble;scale=-1"}, "", "", "scale: must be a finite number > 0"},
      {{"plastic=marble;gaussians=9"}, "", "", "gaussians: must be an integer in [1, 8]"},
      {{"plastic=sigma-a=-1;sigma-s=1"}, "", "", "--sss-material plastic=sigma-a=-1;sigma-s=1: sigma-a"},
      {{"plastic=marble;model=layered"}, "", "", "model: unknown model 'layered'"},
      // Every SSS material set by a spec: a MEDIUM flag has nothing left to change.
      {{"all=marble"}, "skin1", "", "every subsurface material"},
  };
  for (const Case& c : cases) {
    scene::Scene s = load(file);
    const auto before = s.materials;
    app::MaterialOverrideArgs a;
    a.sss_material = c.specs;
    a.medium.preset = c.preset;
    const auto r = apply(s, a);
    const std::string e = error_of(r);
    EXPECT_NE(e.find(c.expected), std::string::npos) << "got: " << e << "\nexpected: " << c.expected;
    for (std::size_t i = 0; i < s.materials.size(); ++i)
      EXPECT_EQ(s.materials[i].sss.enabled, before[i].sss.enabled) << e;
  }
  {  // --scale given alone to a scene without SSS is refused the same way.
    scene::Scene s = load(file);
    app::MaterialOverrideArgs a;
    a.scale = 2.0;
    EXPECT_NE(error_of(apply(s, a)).find("--scale: matches no material"), std::string::npos);
  }
}

TEST(ScaleOption, ScalesEverySubsurfaceMaterialAndKeepsTheLook) {
  // --scale k on a material of scale 1 is its medium with σ × k (SssMaterial::scale).
  auto loaded = scene::load_scene("builtin:materials");
  ASSERT_TRUE(std::holds_alternative<scene::Scene>(loaded));
  scene::Scene s = std::get<scene::Scene>(std::move(loaded));
  app::MaterialOverrideArgs a;
  a.scale = 0.25;
  const auto r = apply(s, a);
  ASSERT_EQ(error_of(r), "");
  EXPECT_EQ(std::get<int>(r), int(s.materials.size()));
  for (const scene::Material& m : s.materials) {
    EXPECT_EQ(m.sss.scale, 0.25) << m.name;
    EXPECT_DOUBLE_EQ(m.sss.effective_medium().sigma_a[0], 0.25 * m.sss.medium.sigma_a[0]) << m.name;
  }
  a.scale = std::nan("");
  EXPECT_NE(error_of(apply(s, a)).find("--scale: must be a finite number > 0"), std::string::npos);
}

// The numbers the warning is made of, against the preset's own coefficients: skin1 on a
// 1 m box (the glTF unit is a metre), and the two warnings a user meets at glTF scale.
TEST(ScatterScale, MeanFreePathAgainstObjectAndPixel) {
  TempDir dir("scatter_scale");
  const auto file = dir.path() / "boxes.glb";
  write_two_boxes(file, 1.0f);
  scene::Scene s = load(file);
  app::MaterialOverrideArgs a;
  a.sss_material = {"plastic=skin1"};
  ASSERT_EQ(error_of(apply(s, a)), "");
  const profiles::Preset& skin1 = *profiles::find_preset("skin1");
  const scene::ScatterScale k = scene::scatter_scale(s, 0, 360);
  double mfp_max = 0.0, diffusion_max = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double st = skin1.sigma_a[c] + skin1.sigma_s_reduced[c];
    mfp_max = std::max(mfp_max, 1.0 / st);
    diffusion_max = std::max(diffusion_max, 1.0 / std::sqrt(3.0 * skin1.sigma_a[c] * st));
  }
  EXPECT_NEAR(k.mfp_max_mm, mfp_max, 1e-9 * mfp_max);
  EXPECT_NEAR(k.diffusion_max_mm, diffusion_max, 1e-9 * diffusion_max);
  EXPECT_NEAR(k.object_mm, 1000.0 * std::sqrt(3.0), 1e-3);  // the box's diagonal
  ASSERT_GT(k.pixel_min_mm, 0.0);
  // The framing camera sees both boxes (2.5 m) from about 3 m: a pixel of a 360-high
  // image covers millimetres there, 2·d·tan(yfov/2)/360, and skin1's 3ℓ (11 mm in red)
  // spans a few of them: visible, barely, and not warned about.
  EXPECT_GT(3.0 * k.diffusion_max_mm, k.pixel_min_mm);
  EXPECT_FALSE(scene::scatter_scale_warning(s, 0, 360).has_value());
  const scene::ScatterScale fine = scene::scatter_scale(s, 0, 10000);
  EXPECT_NEAR(fine.pixel_min_mm, k.pixel_min_mm * 360.0 / 10000.0, 1e-9 * k.pixel_min_mm);

  // The boxes' file with one --sss-material, and its scatter-scale warning (empty: none).
  const auto warning_with = [&](const std::string& spec, scene::ScatterScale* numbers) {
    scene::Scene with = load(file);
    a.sss_material = {spec};
    EXPECT_EQ(error_of(apply(with, a)), "") << spec;
    if (numbers) *numbers = scene::scatter_scale(with, 0, 360);
    return scene::scatter_scale_warning(with, 0, 360).value_or("");
  };

  // skin1 typed in m^-1 (the issue's --sigma-a 32,170,480): 1000 times too dense, 3ℓ of
  // 11 µm, far below a pixel. The warning says so and points the scale the right way.
  scene::ScatterScale m;
  const std::string w = warning_with("plastic=sigma-a=32,170,480;sigma-s=740,880,1010", &m);
  EXPECT_LT(3.0 * m.diffusion_max_mm, m.pixel_min_mm);
  EXPECT_NE(w.find("below one pixel"), std::string::npos) << w;
  EXPECT_NE(w.find("Lower its scale"), std::string::npos) << w;

  // Scale 1e-4: the diffusion lengths grow 10^4 times, past the 1.7 m box in every channel.
  const std::string ww = warning_with("plastic=skin1;scale=1e-4", nullptr);
  EXPECT_NE(ww.find("wider than the object"), std::string::npos) << ww;
  EXPECT_NE(ww.find("Raise its scale"), std::string::npos) << ww;

  // Scale 0.01 (the box scatters like a 1 cm one): a pixel below the scattering and the
  // object wider than it, silent.
  scene::ScatterScale r;
  EXPECT_EQ(warning_with("plastic=skin1;scale=0.01", &r), "");
  EXPECT_GT(3.0 * r.diffusion_max_mm, r.pixel_min_mm);
  EXPECT_LT(r.diffusion_min_mm, r.object_mm);
}

// The default scene is not warned about.
TEST(ScatterScale, TheDefaultScenesAreNotWarnedAbout) {
  for (const char* name : {"builtin:bunny", "builtin:materials", "builtin:sphere"}) {
    auto loaded = scene::load_scene(name);
    ASSERT_TRUE(std::holds_alternative<scene::Scene>(loaded));
    const scene::Scene& s = std::get<scene::Scene>(loaded);
    for (std::size_t i = 0; i < s.materials.size(); ++i) {
      const auto w = scene::scatter_scale_warning(s, i, 360);
      EXPECT_FALSE(w.has_value()) << name << ": " << *w;
    }
  }
}


// The panel's line for skin1 on the 1 m box: the numbers of scatter_scale, readable.
TEST(ScatterScale, ReadoutNamesMfpDiffusionAndObject) {
  scene::ScatterScale k;
  k.mfp_min_mm = 0.0524, k.mfp_max_mm = 0.3, k.diffusion_min_mm = 0.7, k.diffusion_max_mm = 3.66;
  k.object_mm = 1732.05;
  EXPECT_EQ(scene::scatter_scale_readout(k), "mfp 0.052-0.3 mm, diffusion 0.7-3.7 mm; object 1732 mm (0.21%)");
  k.mfp_min_mm = k.mfp_max_mm = 2.0;  // one value for a grey medium
  EXPECT_NE(scene::scatter_scale_readout(k).find("mfp 2 mm,"), std::string::npos);
  k.object_mm = 0.0;  // not drawn: nothing to compare with
  EXPECT_EQ(scene::scatter_scale_readout(k), "");
}

// A medium outside mc-table's tabulated g (issue 18 part 4) is warned about by the viewer
// and the reference, as sss-fit does, naming the material, once for channels sharing g;
// not under a model that does not use the table.
TEST(MaterialWarnings, McTableOutsideItsGRangeIsSaidOnceNamingTheMaterial) {
  TempDir dir("g_warning");
  const auto file = dir.path() / "boxes.glb";
  write_two_boxes(file, 0.05f);
  const auto warnings_with = [&](const std::string& spec) {
    scene::Scene s = load(file);
    app::MaterialOverrideArgs a;
    a.sss_material = {spec};
    EXPECT_EQ(error_of(apply(s, a)), "") << spec;
    s.warnings.clear();
    app::add_material_warnings(s, 360);
    std::string all;
    for (const std::string& w : s.warnings) all += w + "\n";
    return all;
  };
  const std::string medium = "plastic=sigma-a=0.01,0.02,0.03;sigma-s=20,20,20;g=";
  const std::string w = warnings_with(medium + "0.97");
  EXPECT_NE(w.find("material 'plastic': g[R]: g 0.97 > 0.95"), std::string::npos) << w;
  EXPECT_EQ(w.find("g[G]"), std::string::npos) << "one g, said once: " << w;
  EXPECT_EQ(warnings_with(medium + "0.9"), "");
  EXPECT_NE(warnings_with(medium + "-0.2").find("isotropic table"), std::string::npos);
  EXPECT_EQ(warnings_with(medium + "0.97;model=dipole"), "");
}

}  // namespace
}  // namespace sss
