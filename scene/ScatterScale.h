// ScatterScale: how far a material scatters against the size of what it is drawn on and
// the size of a pixel (issue 20, "units at glTF scale"). A glTF in metres with skin on a
// 1 m object scatters over 0.1% of it, invisibly, until SssMaterial::scale is lowered;
// σ typed in m^-1 instead of mm^-1 makes the same mistake a thousand times smaller. The
// viewer's material panel shows these numbers, and the command lines warn with them.
#pragma once

#include "scene/Scene.h"

#include <cstdint>
#include <optional>
#include <string>

namespace sss::scene {

struct ScatterScale {
  // The effective medium's (SssMaterial::effective_medium(): the scale applied; a stack's
  // top layer) reduced mean free path 1/σt' and diffusion length 1/σtr = 1/√(3σa σt'),
  // the smallest and largest over R, G, B, in mm of the object.
  double mfp_min_mm = 0.0, mfp_max_mm = 0.0;
  double diffusion_min_mm = 0.0, diffusion_max_mm = 0.0;
  // The bounding diameter of every instance drawn with the material, mm (0: none).
  double object_mm = 0.0;
  // The smallest pixel footprint on those instances from `camera` (the nearest point of
  // their box, perpendicular to the view), mm; 0 when unknown or the camera is inside.
  double pixel_min_mm = 0.0;
};

// For material `material` of `scene`, seen by scene.cameras[0] (if any) in an image
// `height` pixels high (0: no pixel footprint). A material without SSS gets the object's
// and the pixel's numbers only (the medium's stay 0): the viewer's panel knows the object
// before the user enables subsurface scattering on it.
ScatterScale scatter_scale(const Scene& scene, std::size_t material, std::uint32_t height = 0);
// The medium's numbers for `sss` with the object's and the pixel's given (the viewer's
// editor measures the object once and the medium at every edit).
ScatterScale scatter_scale(const SssMaterial& sss, double object_mm, double pixel_min_mm = 0.0);

// One line for the material panel: the reduced mfp and diffusion lengths (min-max over
// R, G, B) against the object's diameter, e.g. "mfp 0.52-3.4 mm, diffusion 1.1-6.2 mm;
// object 95 mm (6.5%)". Empty when the object is not known.
std::string scatter_scale_readout(const ScatterScale& s);

// A warning when the material's scattering cannot be what the user meant, naming the
// material and the numbers:
// - below a pixel everywhere: 3 diffusion lengths of the widest channel (where the
//   profile's far tail exp(-r/ℓ) has fallen to e^-3 = 5%) are less than the smallest
//   pixel footprint on the object, so every screen-space kernel is under one pixel;
// - wider than the object: the narrowest channel's diffusion length is longer than the
//   object's bounding diameter, so light spreads through all of it in every channel.
// Each names SssMaterial::scale, which multiplies the distances the medium sees (so a
// lower scale scatters further: the opposite of Blender's Subsurface Scale).
std::optional<std::string> scatter_scale_warning(const Scene& scene, std::size_t material,
                                                 std::uint32_t height);
std::optional<std::string> scatter_scale_warning(const Material& material, const ScatterScale& s);

}  // namespace sss::scene
