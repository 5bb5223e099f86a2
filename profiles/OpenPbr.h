// OpenPBR's and Autodesk Standard Surface's subsurface parameters as a medium (issue 21).
// Facts and sources: ../shared/research/materials-standards.md §2.
//
// OpenPBR v1.1.1 "Subsurface": subsurface_color C (the colour seen, [0, 1]³), the mean
// free path per channel r = subsurface_radius × subsurface_radius_scale, so μt = 1/r,
// subsurface_scatter_anisotropy g (Henyey-Greenstein), specular_ior the boundary's η.
// The spec gives no mandatory C → albedo map; its informative one (index-matched, no
// specular term) is van de Hulst's relation
//     C = (1 - s)(1 - 0.139 s) / (1 + 1.17 s),   s² = (1 - α) / (1 - g α),
// inverted as s = 4.09712 + 4.20863 C - √(9.59217 + 41.6808 C + 17.7126 C²),
// α = (1 - s²) / (1 - g s²); then σs = α μt, σa = (1 - α) μt. It is also the g-aware
// inversion of glTF's KHR_materials_scatter draft, so an asset looks here as it does in
// the Khronos sample renderer. 4.09712 = 1.139 / 0.278 and 4.20863 = 1.17 / 0.278 are
// the quadratic's own coefficients (derived).
//
// The project's own inversion (AlbedoInversion::Model) instead finds the albedo whose
// total diffuse reflectance under the chosen model, with the boundary at specular_ior,
// is C (profiles/ArtistMapping.h), μt staying 1/r. It accounts for the boundary's
// internal reflection, which van de Hulst's index-matched relation leaves out, so at
// η = 1.4 it scatters more for the same colour (README "OpenPBR and Standard Surface").
//
// Standard Surface v1.0.1.1: subsurface_color, subsurface_radius (a colour: the mean free
// path per channel), subsurface_scale (a multiplier), subsurface_anisotropy, specular_IOR.
// Its radius colour is OpenPBR's radius_scale normalised by its largest channel, that
// channel times subsurface_scale OpenPBR's radius (derived; the two are the same medium).
//
// Colours are taken as linear Rec.709 (glTF's and the renderer's space). OpenPBR's
// default space is ACEScg: convert such colours first. Lengths are in mm, as everywhere
// in the project's materials (OpenPBR's are in scene units).
#pragma once

#include "profiles/Medium.h"
#include "profiles/Profile.h"

#include <optional>
#include <string_view>
#include <variant>

namespace sss::profiles {

// van de Hulst's relation, as above: the multi-scatter albedo (the colour C) of a
// single-scattering albedo α under g, and its inverse clamped to [0, 1].
double multiscatter_albedo(double single_scattering, double g);
double single_scattering_albedo(double multiscatter, double g);

enum class AlbedoInversion {
  VanDeHulst,  // the specs' (OpenPBR, KHR_materials_scatter): index-matched
  Model,       // the project's: the chosen model's total reflectance at the boundary's η
};
std::string_view albedo_inversion_name(AlbedoInversion inversion);  // "van-de-hulst" | "model"
std::optional<AlbedoInversion> parse_albedo_inversion(std::string_view name);

struct OpenPbrSubsurface {
  Rgb color{0.8, 0.8, 0.8};          // subsurface_color, linear Rec.709
  double radius_mm = 1.0;            // subsurface_radius
  Rgb radius_scale{1.0, 0.5, 0.25};  // subsurface_radius_scale
  double anisotropy = 0.0;           // subsurface_scatter_anisotropy
  double ior = 1.5;                  // specular_ior

  // r = radius × radius_scale per channel, in mm.
  Rgb mean_free_path_mm() const;
};

struct StandardSurfaceSubsurface {
  Rgb color{1.0, 1.0, 1.0};   // subsurface_color, linear Rec.709
  Rgb radius{1.0, 1.0, 1.0};  // subsurface_radius: mean free path per channel, × scale
  double scale = 1.0;         // subsurface_scale, mm
  double anisotropy = 0.0;    // subsurface_anisotropy
  double ior = 1.5;           // specular_IOR
};

OpenPbrSubsurface openpbr_from_standard_surface(const StandardSurfaceSubsurface& s);
StandardSurfaceSubsurface standard_surface_from_openpbr(const OpenPbrSubsurface& p);

// Standard Surface's own checks (radius > 0 per channel, a finite scale > 0), then
// OpenPBR's on its equivalent, every error named as Standard Surface spells the field:
// "subsurface_radius[1]", "subsurface_scale", "specular_IOR".
std::optional<FieldError> validate(const StandardSurfaceSubsurface& s);

// What the project can render: C strictly inside (0, 1) per channel (0 scatters nothing,
// 1 absorbs nothing and has no finite diffusion length), radius > 0, radius_scale in
// (0, 1] (0 would be an infinite μt), |g| < 1, ior in the models' η range. Errors name
// the OpenPBR field: "subsurface_color[1]", "subsurface_radius", "specular_ior".
std::optional<FieldError> validate(const OpenPbrSubsurface& p);

// The medium (σa, σs, g, η per channel in mm^-1, semi-infinite) by `inversion`; `model`
// is the model whose total reflectance AlbedoInversion::Model inverts (mc inverts through
// mc-table, whose total is the same walk tabulated; layered cannot invert a single
// medium and is refused). Errors as validate's, or "subsurface_color[1]" where the model
// cannot reach that colour.
std::variant<Medium, FieldError> medium_from_openpbr(const OpenPbrSubsurface& p,
                                                     AlbedoInversion inversion, Model model,
                                                     const ModelOptions& opt = {});

// OpenPBR's parameters of a medium by the spec's forward map (what Babylon.js writes):
// r = 1/σt per channel, radius = its largest channel, radius_scale = r / radius,
// color = van de Hulst's C of σs/σt under the channels' mean g, ior = the mean η. A
// medium_from_openpbr(..., VanDeHulst) of it is the same medium within the inversion's
// rounded constants (where g is the same in every channel).
OpenPbrSubsurface openpbr_from_medium(const Medium& m);

}  // namespace sss::profiles
