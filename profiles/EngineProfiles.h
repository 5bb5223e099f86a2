// A fitted material as the engines' own subsurface profile assets (issue 21), so that an
// engineer who fits a profile here does not retype it into Unity HDRP or Unreal. Facts
// and sources: ../shared/research/materials-standards.md §3.
//
// Both engines draw Burley's normalized diffusion (Christensen & Burley 2015),
//     R(r) = A (e^{-r/d} + e^{-r/3d}) / (8π d r),   ∫ 2πr R dr = A,
// with one distance d per channel. fit_burley_shape finds, per channel, the d whose
// shape is closest to the project's profile by least squares: it minimises the relative
// L2 error of r·R(r)/A with the linear measure dr (the Gaussian fit's metric,
// GaussianFit.h) over d, the albedo A being the engine's base colour. The error is
// reported beside every export, as the Gaussian fit's is.
//
// Unity HDRP (DiffusionProfileSettings, a YAML .asset with its .meta):
//   scatteringDistance (colour) × scatteringDistanceMultiplier = the fitted d in mm (HDRP's
//   reference page: "when the world scale is 1, this value is in millimeters"; an older
//   page says metres: unverified), worldScale the engine's metres per unit, ior the
//   medium's η (clamped to HDRP's [1, 2]), texturingMode 0 PreAndPostScatter for the
//   pre-post albedo mode and 1 PostScatter otherwise, and for a slab transmissionMode 1
//   ThinObject, thicknessRemap (0, thickness mm) and transmissionTint the ratio of the
//   project's total transmittance to HDRP's 0.25 (e^{-t/d} + 3 e^{-t/3d}) at that
//   thickness (ComputeTransmittanceDisney, its volume albedo premultiplied by 0.25), so
//   that the light through the slab has the project's colour; a semi-infinite medium keeps
//   HDRP's defaults (Regular, (0, 5) mm, white). The script guid b2686e09ec7aef44bad2843e4416f057
//   and the version 2 layout are HDRP's (DiffusionProfileSettings.cs); the .meta's guid
//   is derived from the name and content (stable across exports of the same profile).
//
// Unreal (USubsurfaceProfile; the .uasset is binary, so a JSON of its settings and a
// Python script for the editor that creates the asset): SurfaceAlbedo = the model's total
// diffuse reflectance, MeanFreePathColor × MeanFreePathDistance = the mean free path
// 1/σt per channel in cm (distance the longest channel's, colour each over it),
// WorldUnitScale as given (Unreal's default 0.1), IOR the medium's η, Burley and mean free
// path mode on. Unreal converts the mean free path to its own d through the albedo
// (SubsurfaceProfile.cpp; not reproduced here): the fitted d is written beside it as
// information, and its error is that of the best Burley shape.
#pragma once

#include "profiles/Medium.h"
#include "profiles/Profile.h"

#include <string>

namespace sss::profiles {

struct BurleyShapeFit {
  Rgb d_mm{};            // Burley's d per channel
  Rgb relative_error{};  // ‖r(R/A - R_d)‖₂ / ‖r R/A‖₂ on a log grid, dr measure
};

// Throws std::invalid_argument for a profile with a non-positive total in some channel.
BurleyShapeFit fit_burley_shape(const RgbProfile& profile);

// What both exports read from a material.
struct EngineProfileSource {
  std::string name;           // the asset's name (sanitised for Unity and Unreal)
  Medium medium;              // the effective medium (the material's scale applied), mm^-1
  bool pre_post_albedo = false;
  double world_scale = 1.0;   // HDRP worldScale (m per unit) or Unreal WorldUnitScale
};

struct HdrpDiffusionProfile {
  std::string asset, meta;  // NAME.asset and NAME.asset.meta
  BurleyShapeFit fit;
  Rgb transmission_tint{1.0, 1.0, 1.0};
};
// `profile` is the material's RgbProfile (its model's). Throws std::invalid_argument for
// a world scale outside HDRP's [0.001, ∞).
HdrpDiffusionProfile hdrp_diffusion_profile(const EngineProfileSource& source, const RgbProfile& profile);

struct UnrealSubsurfaceProfile {
  std::string json, python;  // NAME.json and NAME.py
  BurleyShapeFit fit;
};
// `content_path` is where the script creates the asset ("/Game/SSS"). Throws
// std::invalid_argument for a world unit scale that is not finite and > 0.
UnrealSubsurfaceProfile unreal_subsurface_profile(const EngineProfileSource& source,
                                                  const RgbProfile& profile,
                                                  const std::string& content_path = "/Game/SSS");

// The name as an identifier both engines accept: letters, digits and '_' (others become '_').
std::string engine_asset_name(const std::string& name);

}  // namespace sss::profiles
