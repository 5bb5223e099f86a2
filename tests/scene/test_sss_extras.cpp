// materials[i].extras.sss: every source, every option, and an error naming the field
// for every bad value.
#include "scene/SssExtras.h"

#include "profiles/Presets.h"

#include "SssExpect.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace sss::scene {
namespace {

SssMaterial parse_ok(std::string_view text) {
  return testing::expect_parsed<SssMaterial>([](std::string_view t) { return parse_sss_extras_text(t); }, text);
}

FieldError parse_error(std::string_view text) {
  return testing::expect_refused([](std::string_view t) { return parse_sss_extras_text(t); }, text);
}

TEST(SssExtras, PresetWithDefaults) {
  const SssMaterial s = parse_ok(R"({"preset": "skin1"})");
  EXPECT_TRUE(s.enabled);
  EXPECT_EQ(s.model, profiles::kDefaultModel);  // no "model" given
  EXPECT_EQ(s.gaussians, 6);
  EXPECT_EQ(s.scale, 1.0);
  EXPECT_EQ(s.albedo_mode, AlbedoMode::PostScatter);
  const profiles::Medium expected = profiles::preset_medium(*profiles::find_preset("skin1"));
  EXPECT_EQ(s.medium.sigma_a, expected.sigma_a);
  EXPECT_EQ(s.medium.sigma_s, expected.sigma_s);
  EXPECT_EQ(s.medium.eta, expected.eta);
  EXPECT_FALSE(s.medium.is_slab());
}

TEST(SssExtras, EveryOption) {
  const SssMaterial s = parse_ok(
      R"({"preset": "marble", "model": "pbd", "gaussians": 8, "scale": 0.5,
          "albedo_mode": "pre-post", "thickness": 20, "enabled": true})");
  EXPECT_EQ(s.model, profiles::Model::Pbd);
  EXPECT_EQ(s.gaussians, 8);
  EXPECT_EQ(s.scale, 0.5);
  EXPECT_EQ(s.albedo_mode, AlbedoMode::PrePost);
  EXPECT_EQ(s.medium.thickness_mm, 20.0);
  EXPECT_NEAR(s.effective_medium().sigma_s[0], 0.5 * s.medium.sigma_s[0], 1e-15);
  EXPECT_NEAR(s.effective_medium().thickness_mm, 40.0, 1e-12);
}

TEST(SssExtras, CoefficientsScalarOrArray) {
  const SssMaterial s = parse_ok(R"({"sigma_a": 0.05, "sigma_s": [1, 2, 3], "g": [0, 0.2, 0.4]})");
  ASSERT_TRUE(std::holds_alternative<CoefficientSource>(s.source));
  EXPECT_EQ(s.medium.sigma_a, (Rgb{0.05, 0.05, 0.05}));
  EXPECT_EQ(s.medium.sigma_s, (Rgb{1, 2, 3}));
  EXPECT_EQ(s.medium.g, (Rgb{0, 0.2, 0.4}));
  EXPECT_EQ(s.medium.eta, (Rgb{1.3, 1.3, 1.3}));  // default
}

// The viewer exports with sss_extras_json: reading the block back must give the same
// material, bit for bit (doubles print round-trip exactly in nlohmann::json), for every
// source kind and every option.
TEST(SssExtras, WrittenBlockReadsBackAsTheSameMaterial) {
  for (const char* text :
       {R"({"preset": "skin1"})",
        R"({"preset": "marble", "model": "pbd", "gaussians": 8, "scale": 0.5,
            "albedo_mode": "pre-post", "thickness": 20})",
        R"({"sigma_a": [0.013, 0.07, 0.3], "sigma_s": [1.1, 2.2, 3.3], "g": [0, 0.2, 0.4],
            "eta": [1.3, 1.4, 1.5], "model": "dipole", "enabled": false})",
        R"({"color": [0.3, 0.2, 0.1], "mfp": [2, 1, 0.5], "g": 0.1, "eta": 1.4,
            "thickness": 3, "model": "multipole", "gaussians": 3})",
        R"({"openpbr": {"subsurface_color": [0.671, 0.505, 0.371], "subsurface_radius": 1.5,
            "subsurface_radius_scale": [0.482, 0.169, 0.109], "specular_ior": 1.4}})",
        R"({"openpbr": {"subsurface_color": 0.5, "subsurface_scatter_anisotropy": 0.3},
            "albedo_inversion": "model", "model": "better-dipole", "thickness": 12})",
        R"({"standard_surface": {"subsurface_color": [0.8, 0.5, 0.3],
            "subsurface_radius": [0.9, 0.3, 0.15], "subsurface_scale": 2.5}, "scale": 2})"}) {
    SCOPED_TRACE(text);
    const SssMaterial a = parse_ok(text);
    const nlohmann::json written = sss_extras_json(a);
    const SssMaterial b = parse_ok(written.dump());
    testing::expect_same_sss(b, a);
  }
}

TEST(SssExtras, ArtistColourAndMeanFreePath) {
  const SssMaterial s = parse_ok(R"({"color": [0.6, 0.4, 0.2], "mfp": 2})");
  ASSERT_TRUE(std::holds_alternative<ArtistSource>(s.source));
  const profiles::RgbProfile profile(s.model, s.medium);
  const Rgb total = profile.total_reflectance();
  EXPECT_NEAR(total[0], 0.6, 1e-6);
  EXPECT_NEAR(total[2], 0.2, 1e-6);
}

// extras.sss.openpbr is OpenPBR's mapping (profiles/OpenPbr.h, tested against the spec
// there); here: every key reaches it, defaults are the spec's, Standard Surface is the
// same medium as its OpenPBR equivalent, and a weight of 0 turns the material off.
TEST(SssExtras, OpenPbrAndStandardSurfaceBlocks) {
  const SssMaterial s = parse_ok(R"({"openpbr": {"subsurface_color": [0.671, 0.505, 0.371],
      "subsurface_radius": 1.5, "subsurface_radius_scale": [0.482, 0.169, 0.109],
      "subsurface_scatter_anisotropy": 0.2, "specular_ior": 1.4, "subsurface_weight": 1}})");
  ASSERT_TRUE(std::holds_alternative<OpenPbrSource>(s.source));
  profiles::OpenPbrSubsurface p;
  p.color = {0.671, 0.505, 0.371};
  p.radius_mm = 1.5;
  p.radius_scale = {0.482, 0.169, 0.109};
  p.anisotropy = 0.2;
  p.ior = 1.4;
  const auto want = profiles::medium_from_openpbr(p, profiles::AlbedoInversion::VanDeHulst, s.model);
  ASSERT_TRUE(std::holds_alternative<profiles::Medium>(want));
  EXPECT_EQ(s.medium.sigma_a, std::get<profiles::Medium>(want).sigma_a);
  EXPECT_EQ(s.medium.sigma_s, std::get<profiles::Medium>(want).sigma_s);
  EXPECT_EQ(s.medium.eta[2], 1.4);
  EXPECT_TRUE(s.enabled);

  // The spec's defaults: colour 0.8, radius 1, radius_scale (1, 0.5, 0.25), ior 1.5.
  const SssMaterial d = parse_ok(R"({"openpbr": {}})");
  EXPECT_NEAR((d.medium.sigma_a[2] + d.medium.sigma_s[2]) * 0.25, 1.0, 1e-14);
  EXPECT_EQ(d.medium.eta[0], 1.5);

  const SssMaterial ss = parse_ok(R"({"standard_surface": {"subsurface_color": [0.671, 0.505, 0.371],
      "subsurface_radius": [0.723, 0.2535, 0.1635], "subsurface_scale": 1.0,
      "subsurface_anisotropy": 0.2, "specular_IOR": 1.4}})");
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(ss.medium.sigma_s[c], s.medium.sigma_s[c], 1e-12 * s.medium.sigma_s[c]) << c;
    EXPECT_NEAR(ss.medium.sigma_a[c], s.medium.sigma_a[c], 1e-12 * s.medium.sigma_a[c]) << c;
  }
  // A weight of 0: off, with the default (resolved) medium that every material without
  // subsurface scattering has, so that it exports and reads back; the values are still
  // type-checked but not range-checked (the fuzzer's find: a radius of 0 beside weight 0
  // left the material without a medium).
  for (const char* text : {R"({"openpbr": {"subsurface_weight": 0, "subsurface_radius": 0}})",
                           R"({"standard_surface": {"subsurface": 0}})"}) {
    const SssMaterial off = parse_ok(text);
    EXPECT_FALSE(off.enabled) << text;
    EXPECT_FALSE(off.effective_medium().validate().has_value()) << text;
    testing::expect_same_sss(parse_ok(sss_extras_json(off).dump()), off);
  }
  EXPECT_EQ(parse_error(R"({"openpbr": {"subsurface_weight": 0, "subsurface_radius": "x"}})").field,
            "openpbr.subsurface_radius");
  // The project's inversion scatters more for the same colour behind a boundary.
  const SssMaterial own = parse_ok(R"({"openpbr": {"subsurface_color": 0.5, "specular_ior": 1.4},
      "albedo_inversion": "model"})");
  const SssMaterial spec = parse_ok(R"({"openpbr": {"subsurface_color": 0.5, "specular_ior": 1.4}})");
  EXPECT_GT(own.medium.sigma_s[0], spec.medium.sigma_s[0]);
}

TEST(SssExtras, ErrorsNameTheField) {
  const std::pair<const char*, std::pair<const char*, const char*>> cases[] = {
      {R"({"sigma_a": [0.1, -1, 0.1], "sigma_s": 1})", {"sigma_a[1]", "must be >= 0 mm^-1, got -1"}},
      {R"({"sigma_a": 0.1, "sigma_s": -1})", {"sigma_s", ">= 0"}},
      {R"({"sigma_a": 0, "sigma_s": 0})", {"sigma_t", "empty"}},
      {R"({"sigma_a": [0.1, 0.1, 0], "sigma_s": 1})", {"sigma_a[2]", "albedo of 1"}},
      {R"({"sigma_a": 0.1, "sigma_s": 1, "eta": 0})", {"eta", "> 0, got 0"}},
      {R"({"sigma_a": 0.1, "sigma_s": 1, "eta": [1.3, 1.3, -2]})", {"eta[2]", "> 0"}},
      {R"({"sigma_a": 0.1, "sigma_s": 1, "g": 1})", {"g", "(-1, 1), got 1"}},
      {R"({"sigma_a": 0.1, "sigma_s": 1, "g": [0, -1, 0]})", {"g[1]", "(-1, 1)"}},
      {R"({"sigma_a": 0.1})", {"sigma_s", "required"}},
      {R"({"sigma_a": [1, 2], "sigma_s": 1})", {"sigma_a", "array of 3"}},
      {R"({"sigma_a": [1, "x", 2], "sigma_s": 1})", {"sigma_a[1]", "number"}},
      {R"({"preset": "jade"})", {"preset", "unknown preset \"jade\"; expected one of apple"}},
      {R"({"preset": 3})", {"preset", "string"}},
      {R"({"preset": "spectralon"})", {"preset", "cannot be rendered"}},
      {R"({"preset": "skin1", "g": 0.3})", {"g", "preset"}},
      {R"({"preset": "skin1", "gaussians": 9})", {"gaussians", "[1, 8], got 9"}},
      {R"({"preset": "skin1", "gaussians": 0})", {"gaussians", "[1, 8], got 0"}},
      {R"({"preset": "skin1", "gaussians": 2.5})", {"gaussians", "integer"}},
      {R"({"preset": "skin1", "gaussians": 4294967302})", {"gaussians", "4294967302"}},
      {R"({"preset": "skin1", "scale": -1})", {"scale", "> 0"}},
      {R"({"preset": "skin1", "model": "quadpole"})", {"model", "dipole, better-dipole"}},
      {R"({"preset": "skin1", "albedo_mode": 1})", {"albedo_mode", "post-scatter"}},
      {R"({"preset": "skin1", "thickness": 0})", {"thickness", "> 0"}},
      {R"({"preset": "skin1", "enabled": "yes"})", {"enabled", "true or false"}},
      {R"({"color": [1.2, 0.5, 0.5], "mfp": 1})", {"color[0]", "between 0 and 1, got 1.2"}},
      {R"({"color": 0, "mfp": 1})", {"color", "between 0 and 1, got 0"}},
      {R"({"color": 0.5, "mfp": [1, 1, -3]})", {"mfp[2]", "> 0 mm, got -3"}},
      {R"({"color": 0.5, "mfp": 1, "g": [0, 0, 0]})", {"g", "single number"}},
      {R"({"color": 0.5, "mfp": 1, "model": "mc"})", {"model", "mc"}},
      {R"({"color": 0.5})", {"mfp", "required"}},
      {R"({"colour": 0.5})", {"colour", "unknown field"}},
      {R"({})", {"", "needs one of"}},
      {R"({"preset": "skin1", "color": 0.5, "mfp": 1})", {"", "only one"}},
      {R"([1, 2, 3])", {"", "JSON object"}},
      {R"({"preset": )", {"", "not valid JSON"}},
      {R"({"openpbr": {"subsurface_color": [0.5, 1, 0.5]}})", {"openpbr.subsurface_color[1]", "between 0 and 1"}},
      {R"({"openpbr": {"subsurface_radius": 0}})", {"openpbr.subsurface_radius", "> 0"}},
      {R"({"openpbr": {"subsurface_radius": "1"}})", {"openpbr.subsurface_radius", "number"}},
      {R"({"openpbr": {"subsurface_radius_scale": [1, 0, 1]}})", {"openpbr.subsurface_radius_scale[1]", "(0, 1]"}},
      {R"({"openpbr": {"subsurface_scatter_anisotropy": -1}})", {"openpbr.subsurface_scatter_anisotropy", "(-1, 1)"}},
      {R"({"openpbr": {"specular_ior": 0.5}})", {"openpbr.specular_ior", "[1, 2.5]"}},
      {R"({"openpbr": {"subsurface_weight": 0.5}})", {"openpbr.subsurface_weight", "0 (no subsurface) or 1"}},
      {R"({"openpbr": {"subsurface_radius": 1, "transmission_depth": 1}})", {"openpbr.transmission_depth", "unknown field"}},
      {R"({"openpbr": [0.5]})", {"openpbr", "JSON object"}},
      {R"({"openpbr": {}, "preset": "skin1"})", {"preset", "cannot be combined with openpbr"}},
      {R"({"openpbr": {}, "standard_surface": {}})", {"standard_surface", "give one"}},
      {R"({"openpbr": {}, "albedo_inversion": "exact"})", {"albedo_inversion", "van-de-hulst"}},
      {R"({"preset": "skin1", "albedo_inversion": "model"})", {"albedo_inversion", "only to openpbr"}},
      {R"({"standard_surface": {"subsurface_color": 0.5, "subsurface_radius": [1, -1, 1]}})", {"standard_surface.subsurface_radius[1]", "> 0"}},
      {R"({"standard_surface": {"subsurface_color": 0.5, "subsurface_scale": 0}})", {"standard_surface.subsurface_scale", "> 0"}},
      {R"({"standard_surface": {"subsurface_color": 0.5, "specular_IOR": 9}})",
       {"standard_surface.specular_IOR", "[1, 2.5]"}},
      {R"({"standard_surface": {"subsurface_radius": [1, 1, 1]}})", {"standard_surface.subsurface_color", "required"}},
      {R"({"standard_surface": {"subsurface_color": 0.5, "subsurface_radius": [1, 1, 1], "foo": 1}})",
       {"standard_surface.foo", "unknown field; expected one of subsurface, subsurface_color"}},
      {R"({"standard_surface": {"subsurface_color": [0.5, 0.5, 1.5]}})", {"standard_surface.subsurface_color[2]", "between 0 and 1"}},
      {R"({"standard_surface": {"subsurface": 0.3}})", {"standard_surface.subsurface", "0 (no subsurface) or 1"}},
  };
  for (const auto& [text, want] : cases) {
    const FieldError e = parse_error(text);
    EXPECT_EQ(e.field, want.first) << text << " -> " << e.what();
    EXPECT_NE(e.message.find(want.second), std::string::npos) << text << " -> " << e.what();
  }
}

TEST(SssExtras, DeepJsonIsRefusedWithoutRecursion) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_NE(parse_error(deep).message.find("nests deeper"), std::string::npos);
}

TEST(SssExtras, MakeSssMaterialChecksItsArguments) {
  EXPECT_EQ(std::get<FieldError>(make_sss_material(PresetSource{"skin1"}, profiles::Model::Dipole, 9)).field,
            "gaussians");
  EXPECT_EQ(std::get<FieldError>(make_sss_material(PresetSource{"skin1"}, profiles::Model::Dipole, 6,
                                                   std::nan(""))).field,
            "scale");
  EXPECT_THROW(preset_sss_material("jade"), std::invalid_argument);
  EXPECT_EQ(albedo_mode_name(AlbedoMode::PrePost), "pre-post");
  EXPECT_EQ(parse_albedo_mode("post-scatter"), AlbedoMode::PostScatter);
  EXPECT_EQ(parse_albedo_mode("x"), std::nullopt);
}

}  // namespace
}  // namespace sss::scene

namespace sss::scene {
namespace {

// extras.sss.layers (issue 19): a stack is the material's medium and model.
constexpr const char* kTwoLayers = R"({"layers": [
  {"thickness_mm": 0.25, "sigma_a": [0.3, 0.5, 0.8], "sigma_s": 8, "eta": 1.4},
  {"sigma_a": 0.02, "sigma_s": 2, "eta": 1.4}], "gaussians": 5, "scale": 2})";

TEST(SssExtrasLayers, AStackIsTheMediumAndTheModel) {
  const auto parsed = parse_sss_extras_text(kTwoLayers);
  ASSERT_TRUE(std::holds_alternative<SssMaterial>(parsed)) << std::get<FieldError>(parsed).what();
  const SssMaterial& m = std::get<SssMaterial>(parsed);
  EXPECT_EQ(m.model, profiles::Model::Layered);
  ASSERT_EQ(m.layers.size(), 2u);
  EXPECT_EQ(m.layers[0].sigma_a[2], 0.8);
  EXPECT_EQ(m.layers[0].thickness_mm, 0.25);
  EXPECT_FALSE(m.layers[1].is_slab());
  EXPECT_EQ(m.medium.sigma_s[0], 8.0);  // the top layer: what single scattering sees
  EXPECT_EQ(m.gaussians, 5);
  // The scale shrinks every layer (σ x 2, thickness / 2), as it does one medium.
  const auto eff = m.effective_layers();
  EXPECT_EQ(eff[0].sigma_s[1], 16.0);
  EXPECT_EQ(eff[0].thickness_mm, 0.125);
  EXPECT_FALSE(m.transmits());
  // The material's profile is the layered model of that effective stack.
  const auto p = m.profile();
  EXPECT_EQ(p.model(), profiles::Model::Layered);
  EXPECT_EQ(p.total_reflectance(), profiles::make_layered_rgb_profile(eff).total_reflectance());
}

TEST(SssExtrasLayers, WrittenBlockReadsBackAsTheSameStack) {
  const SssMaterial a = std::get<SssMaterial>(parse_sss_extras_text(kTwoLayers));
  const auto b = parse_sss_extras(sss_extras_json(a));
  ASSERT_TRUE(std::holds_alternative<SssMaterial>(b)) << std::get<FieldError>(b).what();
  const SssMaterial& m = std::get<SssMaterial>(b);
  ASSERT_EQ(m.layers.size(), a.layers.size());
  for (std::size_t k = 0; k < a.layers.size(); ++k) {
    EXPECT_EQ(m.layers[k].sigma_a, a.layers[k].sigma_a);
    EXPECT_EQ(m.layers[k].sigma_s, a.layers[k].sigma_s);
    EXPECT_EQ(m.layers[k].g, a.layers[k].g);
    EXPECT_EQ(m.layers[k].eta, a.layers[k].eta);
    EXPECT_EQ(m.layers[k].thickness_mm, a.layers[k].thickness_mm);
  }
  EXPECT_EQ(m.model, profiles::Model::Layered);
  EXPECT_EQ(m.scale, a.scale);
  EXPECT_EQ(m.gaussians, a.gaussians);
}

TEST(SssExtrasLayers, ErrorsNameTheLayerOrTheConflictingKey) {
  auto field = [](const std::string& text) {
    const auto r = parse_sss_extras_text(text);
    return std::holds_alternative<FieldError>(r) ? std::get<FieldError>(r).field : "no error";
  };
  EXPECT_EQ(field(R"({"layers": [{"sigma_a": [0.1, 0.1, -1], "sigma_s": 1}]})"),
            "layers[0].sigma_a[2]");
  EXPECT_EQ(field(R"({"layers": [{"sigma_a": 0.1, "sigma_s": 1}], "preset": "skin1"})"), "preset");
  EXPECT_EQ(field(R"({"layers": [{"sigma_a": 0.1, "sigma_s": 1}], "model": "dipole"})"), "model");
  EXPECT_EQ(field(R"({"layers": [{"sigma_a": 0.1, "sigma_s": 1}], "thickness": 2})"), "thickness");
  EXPECT_EQ(field(R"({"layers": [{"sigma_a": 0.1, "sigma_s": 1}, {"sigma_a": 0.1, "sigma_s": 1}]})"),
            "layers[0].thickness_mm");
  EXPECT_EQ(field(R"({"layers": []})"), "layers");
  EXPECT_EQ(field(R"({"layers": [{"sigma_a": 0.1, "sigma_s": 1}], "gaussians": 9})"), "gaussians");
}

}  // namespace
}  // namespace sss::scene
