// The glTF material extensions that describe a participating medium (issue 21), read
// into the project's SssMaterial so that an artist's file from Blender, Babylon.js or the
// Khronos sample viewer scatters here without extras.sss. Facts and sources:
// ../shared/research/materials-standards.md; the extensions' READMEs in KhronosGroup/glTF.
//
//   KHR_materials_volume (ratified): thicknessFactor (mesh space; 0 = thin-walled, > 0 a
//     volume), attenuationDistance d (world units, > 0; absent = infinite) and
//     attenuationColor c (each in (0, 1]): the extinction σt = -ln(c) / d per channel.
//   KHR_materials_volume_scatter (draft, KhronosGroup/glTF PR #2453): the multi-scatter
//     albedo ρms as multiscatterColorFactor, multiscatterColor or scatterAlbedo (the
//     names its drafts have used; default 0), scatterAnisotropy g (HG, |g| < 1). Its
//     σt covers absorption and scattering; the single-scattering albedo by its g-free
//     inversion (Kulla & Conty 2017), ρss = 1 - s².
//   KHR_materials_scatter (draft, PR #2579, aligned with OpenPBR): scatterStrengthFactor,
//     scatterFactor or scatterWeight (default 0), multiscatterColorFactor (default 1),
//     scatterAnisotropy; volumetric when KHR_materials_volume has thicknessFactor > 0,
//     else thin-walled. ρms* = strength x ρms, ρss by the g-aware inversion
//     ρss = (1 - s²) / (1 - g s²).
//   KHR_materials_ior: ior (default 1.5, >= 1; 0 = spec-gloss compatibility), the
//     medium's η and the specular F0 = ((ior - 1) / (ior + 1))².
//   KHR_materials_transmission (transmissionFactor, [0, 1], default 0) and
//     KHR_materials_diffuse_transmission (diffuseTransmissionFactor, [0, 1], default 0;
//     diffuseTransmissionColorFactor, each in [0, 1], default 1): the boundary through
//     which light enters the volume. Both factors 0: no light enters, no medium.
//
// s = 4.09712 + 4.20863 ρms - sqrt(9.59217 + 41.6808 ρms + 17.7126 ρms²) is the root of
// van de Hulst's relation ρms = (1 - s)(1 - 0.139 s) / (1 + 1.17 s), s² = (1 - ρss) /
// (1 - g ρss) (OpenPBR v1.1.1 "Subsurface"), solved for s: 4.09712 = 1.139 / 0.278,
// 4.20863 = 1.17 / 0.278 (derived).
//
// Then σs = ρss σt, σa = (1 - ρss) σt, in mm^-1 (σt per scene unit / mm per unit).
// Textures (thickness, colour, strength) are not read: the medium is one per material; a
// warning says so.
#pragma once

#include "scene/Material.h"
#include "profiles/OpenPbr.h"

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace sss::scene {

// What materials[i].extensions holds of the medium extensions, checked. Field errors name
// "KHR_materials_volume.attenuationDistance", "KHR_materials_scatter.multiscatterColorFactor[1]".
struct KhrMedium {
  bool volume = false;         // KHR_materials_volume is present
  double thickness_factor = 0.0;
  double attenuation_distance = 0.0;  // 0: absent (infinite)
  Rgb attenuation_color{1.0, 1.0, 1.0};
  enum class Scatter { None, VolumeScatter, Scatter };
  Scatter scatter = Scatter::None;
  Rgb multiscatter{0.0, 0.0, 0.0};  // ρms as the file gives it
  double strength = 1.0;             // KHR_materials_scatter's scatterStrength; 1 otherwise
  double anisotropy = 0.0;
  std::optional<double> ior;         // KHR_materials_ior
  // KHR_materials_transmission's transmissionFactor and KHR_materials_diffuse_transmission's
  // diffuseTransmissionFactor and diffuseTransmissionColorFactor, when present (each
  // factor's default is 0). The volume lets light in only through one of them.
  std::optional<double> transmission;
  std::optional<double> diffuse_transmission;
  Rgb diffuse_transmission_color{1.0, 1.0, 1.0};
  std::vector<std::string> ignored;  // textures and drafts' fields not read, for a warning
  bool any() const { return volume || scatter != Scatter::None || ior.has_value(); }
};

std::variant<KhrMedium, FieldError> parse_khr_medium(const nlohmann::json& extensions);

// van de Hulst's relation and its inverse (profiles/OpenPbr.h, which OpenPBR shares).
using profiles::multiscatter_albedo;
using profiles::single_scattering_albedo;

// The material the extensions describe: an enabled SssMaterial with coefficients (σa, σs,
// g, η; the project's default model and fit), or nullopt when they give no scattering
// medium; `why_not` then says why (thin-walled, no attenuationDistance, a channel with no
// extinction, no absorption at all, an ior outside the models' η range) or is empty when
// there is nothing to say (no scatter extension: a clear or tinted volume). What
// parse_khr_medium accepted is never an error here.
std::optional<SssMaterial> khr_sss_material(const KhrMedium& khr, double mm_per_unit,
                                            std::string& why_not);

// How the transmission extensions were taken, for warnings on a material that scatters:
// neither present (KHR_materials_volume "needs" one; the medium is scattered as if
// diffuseTransmissionFactor were 1), a factor between 0 and 1 (not applied: all light
// that is not reflected specularly enters), a diffuseTransmissionColorFactor other than
// 1 (the boundary's tint, not applied), and KHR_materials_scatter with
// diffuse_transmission (which that draft forbids). Empty when there is nothing to say.
// Both factors 0 is not here: khr_sss_material gives no medium then (no light enters;
// Khronos' sample renderer draws such a surface opaque).
std::vector<std::string> khr_transmission_notes(const KhrMedium& khr);

// What an exported material carries besides extras.sss, so that other tools see its
// medium (an object of extensions; empty for a layered material, which they cannot
// hold): KHR_materials_volume (attenuationDistance d = 1 / max σt, the longest channel's
// mean free path, in scene units, and attenuationColor c = exp(-σt d) in [1/e, 1);
// thicknessFactor the slab's thickness, or d where the medium is semi-infinite: > 0 marks
// it a volume), KHR_materials_volume_scatter (multiscatterColorFactor = van de Hulst's
// colour of σs/σt with g = 0, the g-free relation its draft inverts; scatterAnisotropy
// the channels' mean g), KHR_materials_ior (the channels' mean η) and
// KHR_materials_diffuse_transmission (factor 1: the volume extension needs a transmission
// extension, and Khronos' sample renderer draws volume_scatter only with it). The medium
// is the effective one (the material's scale applied). parse_khr_medium and
// khr_sss_material read it back to the same σa, σs within the inversion's rounding.
nlohmann::json khr_extensions_json(const SssMaterial& material, double mm_per_unit);
// The names khr_extensions_json writes.
inline constexpr const char* kKhrWritten[] = {"KHR_materials_volume", "KHR_materials_volume_scatter",
                                              "KHR_materials_ior", "KHR_materials_diffuse_transmission"};

// The dielectric F0 of an ior (KHR_materials_ior): ((ior - 1) / (ior + 1))².
double ior_f0(double ior);

}  // namespace sss::scene
