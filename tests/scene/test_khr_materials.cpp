// The glTF medium extensions (KhrMaterials.h; issue 21): the albedo inversion against van
// de Hulst's forward relation, σt against Beer's law, every draft's spelling, the
// thin-walled and extinction-free cases, errors that name the extension's field, and a
// file that carries them loading as a scattering material.
#include "GltfTestWriter.h"
#include "tests/common/CliRun.h"

#include "scene/BuiltinScenes.h"
#include "scene/GltfExport.h"
#include "scene/KhrMaterials.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <limits>
#include <variant>


namespace sss::scene {
namespace {

using nlohmann::json;
using testing::GltfTestWriter;
using testing::TempDir;

// single_scattering_albedo inverts multiscatter_albedo (two separate formulas: the quadratic
// root with the spec's rounded constants, and van de Hulst's relation itself). The
// constants 4.09712, 4.20863, 9.59217, 41.6808, 17.7126 are 1.139/0.278, 1.17/0.278 and
// (1.139² - 0.556)/0.278², (2·1.139·1.17 + 0.556)/0.278², 1.17²/0.278² rounded: they move
// s by at most 2.3e-6 + 3.1e-6·C + (3.4e-6 + 1.4e-5·C + 7.5e-6·C²)/(2·sqrt(9.59)) < 1e-5
// (C <= 1). ρss = (1 - s²)/(1 - g s²) changes by |dρ/ds| = 2s(1 - g)/(1 - g s²)² per unit
// of s, at most 2/(1 - g) for g >= 0 and 2(1 - g) for g < 0 (s in [0, 1]): the tolerance.
TEST(KhrMaterials, TheAlbedoInversionUndoesVanDeHulst) {
  double worst = 0.0;
  for (const double g : {-0.9, -0.5, 0.0, 0.3, 0.8, 0.9}) {
    const double tol = std::max(2.0 / (1.0 - g), 2.0 * (1.0 - g)) * 1e-5;
    for (int k = 0; k <= 100; ++k) {
      const double a = k / 100.0;
      const double c = multiscatter_albedo(a, g);
      EXPECT_GE(c, 0.0);
      EXPECT_LE(c, 1.0);
      const double back = single_scattering_albedo(c, g);
      EXPECT_NEAR(back, a, tol) << "g " << g << " rho_ss " << a << " rho_ms " << c;
      worst = std::max(worst, std::fabs(back - a) / tol);
    }
  }
  // The ends: no multiple scattering without single scattering, none lost without absorption.
  EXPECT_NEAR(single_scattering_albedo(0.0, 0.0), 0.0, 2e-5);
  EXPECT_NEAR(single_scattering_albedo(1.0, 0.0), 1.0, 2e-5);
  // Forward scattering needs a higher single-scattering albedo for the same colour.
  EXPECT_GT(single_scattering_albedo(0.5, 0.8), single_scattering_albedo(0.5, 0.0));
  std::printf("[ van de Hulst round trip ] worst |error| / tol %.3f\n", worst);
}

// A colour back through van de Hulst from the inverted albedo: the inversion's s is the
// exact root moved by < 1e-5 (above), the forward relation takes the same s back (s² =
// (1 - ρss)/(1 - g ρss) undoes ρss = (1 - s²)/(1 - g s²)), and |dC/ds| of (1 - s)(1 -
// 0.139 s)/(1 + 1.17 s) is at most 1 + 0.139 + 1.17 = 2.309 (at s = 0): |ΔC| < 2.31e-5.
constexpr double kColourTol = 2.31e-5;

json volume(double distance, json colour, double thickness = 1.0) {
  return {{"thicknessFactor", thickness}, {"attenuationDistance", distance}, {"attenuationColor", colour}};
}

KhrMedium parsed(const json& extensions) {
  auto k = parse_khr_medium(extensions);
  if (auto* e = std::get_if<FieldError>(&k)) ADD_FAILURE() << e->what();
  return std::get_if<KhrMedium>(&k) ? std::get<KhrMedium>(k) : KhrMedium{};
}

// ScatteringSkull's values (glTF-Sample-Assets, CC0): attenuationColor [0.368, 0.486,
// 0.396] at 0.01689 m, multi-scatter colour [0.168, 0.527, 0.591], ior 1.38. σa + σs must
// be σt = -ln(c)/d in mm^-1 (a path of d keeps c: Beer), σs/σt must give back the colour
// through van de Hulst (g-free for the older draft), η = ior.
TEST(KhrMaterials, VolumeScatterGivesBeersExtinctionAndTheColoursAlbedo) {
  const json ext = {{"KHR_materials_volume", volume(0.01689, {0.368, 0.486, 0.396})},
                    {"KHR_materials_volume_scatter", {{"multiscatterColorFactor", {0.168, 0.527, 0.591}}}},
                    {"KHR_materials_ior", {{"ior", 1.38}}}};
  std::string why;
  const auto m = khr_sss_material(parsed(ext), 1000.0, why);
  ASSERT_TRUE(m) << why;
  EXPECT_TRUE(m->enabled);
  ASSERT_TRUE(std::holds_alternative<CoefficientSource>(m->source));
  const double c[3] = {0.368, 0.486, 0.396}, ms[3] = {0.168, 0.527, 0.591};
  for (int k = 0; k < 3; ++k) {
    const double st = m->medium.sigma_a[k] + m->medium.sigma_s[k];
    EXPECT_NEAR(std::exp(-st * 16.89), c[k], 1e-12) << k;
    EXPECT_NEAR(multiscatter_albedo(m->medium.sigma_s[k] / st, 0.0), ms[k], kColourTol) << k;
    EXPECT_DOUBLE_EQ(m->medium.eta[k], 1.38);
    EXPECT_DOUBLE_EQ(m->medium.g[k], 0.0);
  }
}

// Every spelling the drafts used gives the same medium; the newer draft's strength scales
// the colour and its inversion takes g.
TEST(KhrMaterials, EveryDraftSpellingIsRead) {
  const json v = volume(0.005, {0.3, 0.5, 0.7});
  json first;
  for (const char* key : {"multiscatterColorFactor", "multiscatterColor", "scatterAlbedo"}) {
    const json ext = {{"KHR_materials_volume", v}, {"KHR_materials_volume_scatter", {{key, {0.6, 0.7, 0.8}}}}};
    std::string why;
    const auto m = khr_sss_material(parsed(ext), 1000.0, why);
    ASSERT_TRUE(m) << key << ": " << why;
    const json got = {m->medium.sigma_a, m->medium.sigma_s};
    if (first.is_null()) first = got;
    EXPECT_EQ(got, first) << key;
  }
  json strength_first;
  for (const char* key : {"scatterStrengthFactor", "scatterFactor", "scatterWeight"}) {
    const json ext = {{"KHR_materials_volume", v},
                      {"KHR_materials_scatter", {{key, 0.5}, {"multiscatterColorFactor", {0.6, 0.7, 0.8}},
                                                 {"scatterAnisotropy", 0.4}}}};
    std::string why;
    const auto m = khr_sss_material(parsed(ext), 1000.0, why);
    ASSERT_TRUE(m) << key << ": " << why;
    for (int k = 0; k < 3; ++k) {
      const double st = m->medium.sigma_a[k] + m->medium.sigma_s[k];
      EXPECT_NEAR(multiscatter_albedo(m->medium.sigma_s[k] / st, 0.4), 0.5 * (0.6 + 0.1 * k), kColourTol)
          << key << " channel " << k;
      EXPECT_DOUBLE_EQ(m->medium.g[k], 0.4);
    }
    const json got = {m->medium.sigma_a, m->medium.sigma_s};
    if (strength_first.is_null()) strength_first = got;
    EXPECT_EQ(got, strength_first) << key;
  }
}

// What gives no medium says why, and the material stays opaque.
TEST(KhrMaterials, ThinWalledClearAndWhiteMediaAreNotScatteredWithAReason) {
  const json sc = {{"multiscatterColorFactor", {0.5, 0.5, 0.5}}};
  const struct {
    json ext;
    const char* reason;  // empty: nothing to say
  } cases[] = {
      {{{"KHR_materials_volume_scatter", sc}}, "thin-walled"},
      {{{"KHR_materials_volume", volume(0.01, {0.5, 0.5, 0.5}, 0.0)}, {"KHR_materials_volume_scatter", sc}},
       "thin-walled"},
      {{{"KHR_materials_volume", {{"thicknessFactor", 1.0}}}, {"KHR_materials_volume_scatter", sc}},
       "attenuationDistance is absent"},
      {{{"KHR_materials_volume", volume(0.01, {0.5, 1.0, 0.5})}, {"KHR_materials_volume_scatter", sc}},
       "attenuationColor[1] is 1"},
      {{{"KHR_materials_volume", volume(0.01, {0.5, 0.5, 0.5})}, {"KHR_materials_scatter", json::object()}},
       "scatterStrengthFactor is 0"},
      {{{"KHR_materials_volume", volume(0.01, {0.5, 0.5, 0.5})},
        {"KHR_materials_volume_scatter", {{"multiscatterColorFactor", {1.0, 1.0, 1.0}}}}},
       "no absorption"},
      {{{"KHR_materials_volume", volume(0.01, {0.5, 0.5, 0.5})},
        {"KHR_materials_volume_scatter", sc},
        {"KHR_materials_ior", {{"ior", 9.0}}}},
       "cannot take"},
      {{{"KHR_materials_volume", volume(0.01, {0.5, 0.5, 0.5})}}, ""},  // a tinted volume
      {{{"KHR_materials_volume", volume(0.01, {0.5, 0.5, 0.5})},
        {"KHR_materials_volume_scatter", sc},
        {"KHR_materials_transmission", {{"transmissionFactor", 0.0}}},
        {"KHR_materials_diffuse_transmission", json::object()}},
       "no light enters the volume"},
  };
  for (const auto& c : cases) {
    std::string why;
    EXPECT_FALSE(khr_sss_material(parsed(c.ext), 1000.0, why)) << c.ext.dump();
    if (*c.reason == '\0')
      EXPECT_TRUE(why.empty()) << why;
    else
      EXPECT_NE(why.find(c.reason), std::string::npos) << c.ext.dump() << "\n" << why;
  }
}

// The transmission extensions: how much light enters the volume. Any factor > 0 gives the
// medium (with a note where the factor is not 1, or a tint is not applied); neither
// extension gives it too, with a note that the spec lets no light in; values outside
// [0, 1] are refused naming the field.
TEST(KhrMaterials, TransmissionExtensionsDecideWhetherLightEnters) {
  const json vol = volume(0.01, {0.5, 0.5, 0.5});
  const json sc = {{"multiscatterColorFactor", {0.5, 0.5, 0.5}}};
  const struct {
    json extra;
    const char* note;  // empty: nothing to say
  } cases[] = {
      {{{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionFactor", 1.0}}}}, ""},
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}, ""},
      {json::object(), "lets no light in by its spec"},
      {{{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionFactor", 0.5}}}}, "of 0.5 is taken as 1"},
      {{{"KHR_materials_diffuse_transmission",
         {{"diffuseTransmissionFactor", 1.0}, {"diffuseTransmissionColorFactor", {1.0, 0.5, 0.5}}}}},
       "the boundary's tint) is not applied"},
  };
  for (const auto& c : cases) {
    json ext = {{"KHR_materials_volume", vol}, {"KHR_materials_volume_scatter", sc}};
    ext.update(c.extra);
    std::string why;
    const KhrMedium k = parsed(ext);
    EXPECT_TRUE(khr_sss_material(k, 1000.0, why)) << ext.dump() << "\n" << why;
    const auto notes = khr_transmission_notes(k);
    if (*c.note == '\0') {
      EXPECT_TRUE(notes.empty()) << ext.dump();
    } else {
      ASSERT_EQ(notes.size(), 1u) << ext.dump();
      EXPECT_NE(notes[0].find(c.note), std::string::npos) << notes[0];
    }
  }
  for (const json& bad : {json{{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionFactor", 1.5}}}},
                          json{{"KHR_materials_transmission", {{"transmissionFactor", -0.1}}}},
                          json{{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionColorFactor", {1, 2, 1}}}}}}) {
    const auto r = parse_khr_medium(bad);
    ASSERT_TRUE(std::holds_alternative<FieldError>(r)) << bad.dump();
    EXPECT_NE(std::get<FieldError>(r).field.find(bad.begin().key()), std::string::npos) << std::get<FieldError>(r).what();
  }
}

// Values outside what the extensions allow are refused, naming the extension and field.
TEST(KhrMaterials, BadValuesNameTheExtensionAndField) {
  const struct {
    json ext;
    const char* field;
  } cases[] = {
      {{{"KHR_materials_volume", {{"attenuationDistance", 0.0}}}}, "KHR_materials_volume.attenuationDistance"},
      {{{"KHR_materials_volume", {{"attenuationDistance", -1.0}}}}, "KHR_materials_volume.attenuationDistance"},
      {{{"KHR_materials_volume", {{"attenuationColor", {0.5, 0.0, 0.5}}}}}, "KHR_materials_volume.attenuationColor[1]"},
      {{{"KHR_materials_volume", {{"attenuationColor", {0.5, 1.5, 0.5}}}}}, "KHR_materials_volume.attenuationColor[1]"},
      {{{"KHR_materials_volume", {{"attenuationColor", {0.5, 0.5}}}}}, "KHR_materials_volume.attenuationColor"},
      {{{"KHR_materials_volume", {{"thicknessFactor", -0.1}}}}, "KHR_materials_volume.thicknessFactor"},
      {{{"KHR_materials_volume_scatter", {{"scatterAnisotropy", 1.0}}}}, "KHR_materials_volume_scatter.scatterAnisotropy"},
      {{{"KHR_materials_volume_scatter", {{"scatterAlbedo", {0.5, "x", 0.5}}}}}, "KHR_materials_volume_scatter.scatterAlbedo[1]"},
      {{{"KHR_materials_scatter", {{"scatterFactor", 2.0}}}}, "KHR_materials_scatter.scatterFactor"},
      {{{"KHR_materials_scatter", {{"multiscatterColorFactor", {0.5, -0.5, 0.5}}}}}, "KHR_materials_scatter.multiscatterColorFactor[1]"},
      {{{"KHR_materials_ior", {{"ior", 0.5}}}}, "KHR_materials_ior.ior"},
  };
  for (const auto& c : cases) {
    auto k = parse_khr_medium(c.ext);
    const FieldError* e = std::get_if<FieldError>(&k);
    ASSERT_NE(e, nullptr) << c.ext.dump();
    EXPECT_EQ(e->field, c.field) << e->what();
  }
}

// A triangle whose material carries the extensions, written to a file and loaded.
GltfTestWriter khr_file(const json& material) {
  GltfTestWriter w;
  const int pos = w.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  w.push("materials", material);
  w.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"material", 0}}}}});
  w.push("nodes", {{"mesh", 0}});
  w.doc["scenes"] = {{{"nodes", {0}}}};
  w.doc["extensionsUsed"] = {"KHR_materials_volume", "KHR_materials_volume_scatter", "KHR_materials_ior"};
  return w;
}

TEST(KhrMaterials, AFileWithTheExtensionsLoadsAsAScatteringMaterial) {
  const TempDir dir("khr");
  const json ext = {{"KHR_materials_volume", volume(0.01689, {0.368, 0.486, 0.396})},
                    {"KHR_materials_volume_scatter",
                     {{"multiscatterColorFactor", {0.168, 0.527, 0.591}}, {"multiscatterColorTexture", {{"index", 0}}}}},
                    {"KHR_materials_ior", {{"ior", 1.38}}},
                    {"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}};
  khr_file({{"name", "skull"}, {"extensions", ext}}).write_gltf(dir / "k.gltf");
  auto loaded = load_scene((dir / "k.gltf").string());
  ASSERT_TRUE(std::holds_alternative<Scene>(loaded)) << std::get<LoadError>(loaded).what();
  const Scene& s = std::get<Scene>(loaded);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_TRUE(s.materials[0].sss.enabled);
  EXPECT_NEAR(std::exp(-(s.materials[0].sss.medium.sigma_a[0] + s.materials[0].sss.medium.sigma_s[0]) * 16.89),
              0.368, 1e-12);
  // F0 of ior 1.38: ((0.38/2.38)^2) = 0.02549, specular = F0 / 0.04.
  EXPECT_NEAR(s.materials[0].specular, 0.0254927 / 0.04, 1e-5);
  bool texture_warned = false;
  for (const std::string& w : s.warnings) texture_warned |= w.find("multiscatterColorTexture") != std::string::npos;
  EXPECT_TRUE(texture_warned);

  // extras.sss wins, with one warning for the file.
  khr_file({{"name", "both"}, {"extensions", ext}, {"extras", {{"sss", {{"preset", "marble"}}}}}})
      .write_gltf(dir / "both.gltf");
  auto both = load_scene((dir / "both.gltf").string());
  ASSERT_TRUE(std::holds_alternative<Scene>(both));
  const Scene& b = std::get<Scene>(both);
  EXPECT_TRUE(std::holds_alternative<PresetSource>(b.materials[0].sss.source));
  int said = 0;
  for (const std::string& w : b.warnings) said += w.find("extras.sss is used") != std::string::npos;
  EXPECT_EQ(said, 1);

  // A bad value fails the load, naming the file, the material and the field.
  json bad = ext;
  bad["KHR_materials_volume"]["attenuationDistance"] = 0;
  khr_file({{"extensions", bad}}).write_gltf(dir / "bad.gltf");
  auto refused = load_scene((dir / "bad.gltf").string());
  ASSERT_TRUE(std::holds_alternative<LoadError>(refused));
  const std::string msg = std::get<LoadError>(refused).what();
  EXPECT_NE(msg.find("bad.gltf"), std::string::npos) << msg;
  EXPECT_NE(msg.find("materials[0]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("extensions.KHR_materials_volume.attenuationDistance"), std::string::npos) << msg;
}

// What Export writes for other tools reads back as the same medium: σt exactly (exp and
// log), the albedo within the inversion's rounding, 2e-5 for the g-free relation (the
// round-trip test's bound at g = 0), so |Δσs| = |Δσa| <= 2e-5 σt; g and η as written
// (each the mean of equal channels here). The effective medium: the scale is in it. A
// slab's thickness becomes thicknessFactor; a layered material writes none.
TEST(KhrMaterials, WhatExportWritesReadsBackAsTheSameMedium) {
  std::vector<SssMaterial> materials;
  for (const char* preset : {"skin1", "marble", "ketchup", "apple"}) materials.push_back(preset_sss_material(preset));
  materials[1].scale = 2.5;
  materials[2].medium.thickness_mm = 3.0;
  for (const SssMaterial& m : materials) {
    const json ext = khr_extensions_json(m, 1000.0);
    ASSERT_TRUE(ext.contains("KHR_materials_volume")) << ext.dump();
    std::string why;
    const auto back = khr_sss_material(parsed(ext), 1000.0, why);
    ASSERT_TRUE(back) << why;
    const profiles::Medium want = m.effective_medium();
    for (int c = 0; c < 3; ++c) {
      const double st = want.sigma_a[c] + want.sigma_s[c];
      EXPECT_NEAR(back->medium.sigma_a[c] + back->medium.sigma_s[c], st, 1e-12 * st) << ext.dump();
      EXPECT_NEAR(back->medium.sigma_s[c], want.sigma_s[c], 2e-5 * st) << ext.dump();
      EXPECT_NEAR(back->medium.g[c], want.g[c], 1e-12);
      EXPECT_NEAR(back->medium.eta[c], want.eta[c], 1e-12);
    }
    if (want.is_slab()) {
      EXPECT_DOUBLE_EQ(ext["KHR_materials_volume"]["thicknessFactor"].get<double>(), 3.0e-3);
    }
  }
  SssMaterial layered = preset_sss_material("skin1");
  profiles::Medium top = preset_sss_material("skin1").medium;
  top.thickness_mm = 0.5;
  layered.layers = {top, preset_sss_material("marble").medium};
  EXPECT_TRUE(khr_extensions_json(layered, 1000.0).empty());
}

// The Khronos glTF-Validator (npm gltf-validator, installed by scripts/install-deps.sh
// into tools/node) on a file Export wrote: 0 errors. Its output is printed.
int validate(const std::filesystem::path& file, std::string& out) {
  const sss::testing::CliRun r =
      sss::testing::run_shell("node " SSS_SOURCE_DIR "/tools/node/validate.mjs '" + file.string() + "'");
  out += r.out;
  return r.code;
}

TEST(KhrMaterials, ExportWritesTheExtensionsAndTheValidatorFindsNoError) {
  // The shipped bunny (valid: the validator's verdict on it is checked first), its skin1
  // written back with the extensions, as the viewer's Export does.
  const TempDir dir("khr_export");
  const std::filesystem::path in = dir / "bunny.glb", exported = dir / "out.glb";
  std::filesystem::copy_file(SSS_SOURCE_DIR "/assets/bunny.glb", in);
  std::string before;
  ASSERT_EQ(validate(in, before), 0) << before;
  auto loaded = load_scene(in.string());
  ASSERT_TRUE(std::holds_alternative<Scene>(loaded));
  const Scene& s = std::get<Scene>(loaded);
  ASSERT_TRUE(s.materials[0].sss.enabled);
  auto bytes = gltf_with_sss_materials(in.string(), s.materials, exported.string());
  ASSERT_TRUE(std::holds_alternative<std::string>(bytes)) << std::get<LoadError>(bytes).what();
  const std::string& glb = std::get<std::string>(bytes);
  std::ofstream(exported, std::ios::binary) << glb;
  // The JSON chunk: length at byte 12, text from byte 20.
  std::uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  const json doc = json::parse(glb.substr(20, length));
  for (const char* name : kKhrWritten) {
    EXPECT_TRUE(doc["materials"][0]["extensions"].contains(name)) << name;
    EXPECT_NE(std::find(doc["extensionsUsed"].begin(), doc["extensionsUsed"].end(), name), doc["extensionsUsed"].end()) << name;
  }
  EXPECT_FALSE(doc.contains("extensionsRequired"));
  EXPECT_TRUE(doc["materials"][0]["extras"].contains("sss"));
  // Read back: extras.sss wins (the same preset), the extensions give the same medium.
  auto again = load_scene(exported.string());
  ASSERT_TRUE(std::holds_alternative<Scene>(again));
  EXPECT_TRUE(std::holds_alternative<PresetSource>(std::get<Scene>(again).materials[0].sss.source));
  std::string out;
  const int code = validate(exported, out);
  std::printf("%s", out.c_str());
  EXPECT_EQ(code, 0) << out;
  EXPECT_NE(out.find(" 0 errors"), std::string::npos) << out;
}

}  // namespace
// A file written by glTF-Transform (npm; tools/node/variants.mjs: its KHR_materials_volume,
// KHR_materials_ior and KHR_materials_diffuse_transmission, and the draft
// KHR_materials_volume_scatter as a glTF-Transform extension the script defines) on the
// bunny, in metres: the validator finds no error, and the material loads with the medium
// the extensions give, computed here from their definitions:
// - Beer's law over the attenuation distance, 5 mm: exp(-σt · 5) = attenuationColor;
// - the albedo σs/σt = ρss, whose van de Hulst forward relation, (1 - s)(1 - 0.139 s) /
//   (1 + 1.17 s) with s = sqrt(1 - ρss) (the draft is g-free), gives back the
//   multiscatterColor within 2.31e-5 (the bound of the inversion's rounded constants,
//   test_openpbr.cpp);
// - g = scatterAnisotropy and η = ior as written.
// With the file's extras.sss kept, extras.sss wins and one warning says so.
TEST(KhrMaterials, AGltfTransformFileLoadsWithTheMediumItsExtensionsGive) {
  const TempDir dir("khr_gltf_transform");
  const double c[3] = {0.8, 0.5, 0.3}, ms[3] = {0.9, 0.7, 0.5};
  const auto write = [&](const std::filesystem::path& out, bool drop_extras) {
    const json spec = {{"thicknessFactor", 0.02}, {"attenuationDistance", 0.005},
                       {"attenuationColor", {c[0], c[1], c[2]}}, {"ior", 1.4},
                       {"multiscatterColor", {ms[0], ms[1], ms[2]}}, {"scatterAnisotropy", 0.2},
                       {"diffuseTransmissionFactor", 1.0}, {"dropExtras", drop_extras}};
    const auto r = sss::testing::run_shell("node " SSS_SOURCE_DIR "/tools/node/variants.mjs " SSS_SOURCE_DIR
                                           "/assets/bunny.glb '" + out.string() + "' volume --json '" +
                                           spec.dump() + "' 2>&1");
    EXPECT_EQ(r.code, 0) << r.out;
  };
  write(dir / "khr.gltf", true);
  std::string verdict;
  EXPECT_EQ(validate(dir / "khr.gltf", verdict), 0) << verdict;
  EXPECT_NE(verdict.find(" 0 errors"), std::string::npos) << verdict;
  auto loaded = load_scene((dir / "khr.gltf").string());
  ASSERT_TRUE(std::holds_alternative<Scene>(loaded)) << std::get<LoadError>(loaded).what();
  const Scene& s = std::get<Scene>(loaded);
  ASSERT_EQ(s.materials.size(), 1u);
  ASSERT_TRUE(s.materials[0].sss.enabled);
  const profiles::Medium& m = s.materials[0].sss.medium;
  for (int k = 0; k < 3; ++k) {
    const double st = m.sigma_a[k] + m.sigma_s[k];
    EXPECT_NEAR(std::exp(-st * 5.0), c[k], 1e-12) << k;
    const double sq = std::sqrt(1.0 - m.sigma_s[k] / st);
    EXPECT_NEAR((1.0 - sq) * (1.0 - 0.139 * sq) / (1.0 + 1.17 * sq), ms[k], 2.31e-5) << k;
    EXPECT_DOUBLE_EQ(m.g[k], 0.2);
  }
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(m.eta[k], 1.4);

  write(dir / "both.gltf", false);
  auto both = load_scene((dir / "both.gltf").string());
  ASSERT_TRUE(std::holds_alternative<Scene>(both)) << std::get<LoadError>(both).what();
  EXPECT_TRUE(std::holds_alternative<PresetSource>(std::get<Scene>(both).materials[0].sss.source));
  int said = 0;
  for (const std::string& w : std::get<Scene>(both).warnings) said += w.find("extras.sss is used") != std::string::npos;
  EXPECT_EQ(said, 1);
}

}  // namespace sss::scene
