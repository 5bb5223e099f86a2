// The SSS block of a glTF material: materials[i].extras.sss (DESIGN.md §3).
//
//   {"preset": "skin1"}
//   {"sigma_a": [r,g,b], "sigma_s": [r,g,b], "g": g, "eta": e}      (mm^-1)
//   {"color": [r,g,b], "mfp": [r,g,b]}                 (reduced mean free path, mm)
//   {"openpbr": {"subsurface_color": [r,g,b], "subsurface_radius": mm,
//                "subsurface_radius_scale": [r,g,b], "subsurface_scatter_anisotropy": g,
//                "specular_ior": e, "subsurface_weight": 0 | 1}}
//   {"standard_surface": {"subsurface_color": [r,g,b], "subsurface_radius": [r,g,b],
//                "subsurface_scale": mm, "subsurface_anisotropy": g, "specular_IOR": e,
//                "subsurface": 0 | 1}}
//       OpenPBR's or Standard Surface's subsurface parameters (profiles/OpenPbr.h): each
//       key optional with the spec's default; colours linear Rec.709; lengths in mm; a
//       weight of 0 is "enabled": false. With "albedo_inversion": "van-de-hulst" (the
//       spec's, default) or "model" (the material's model's total reflectance).
//   {"layers": [{...}, ...]}      a stack, top first (SssLayers.h; model layered, no
//                                  "model", "thickness" or other medium keys with it)
// plus, with any of them: "model" (dipole | better-dipole | pbd | burley | multipole |
// mc | mc-table, default profiles::kDefaultModel = mc-table), "gaussians" (1..8, default 6), "scale" (> 0, default 1),
// "albedo_mode" ("post-scatter" | "pre-post"), "thickness" (mm, default infinite),
// "enabled" (default true). σa, σs, g, η, colour and mfp take a number (all channels)
// or an array of 3. With a colour, g and η must be single numbers.
//
// Errors name the field inside the block as the user wrote it: "sigma_a[1]" for the
// second array element, "g" for a single number, "foo" for an unknown key.
#pragma once

#include "scene/Material.h"

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string_view>
#include <variant>

namespace sss::scene {

std::variant<SssMaterial, FieldError> parse_sss_extras(const nlohmann::json& sss);

// The same from JSON text: the entry point for fuzzing and for command-line tools.
std::variant<SssMaterial, FieldError> parse_sss_extras_text(std::string_view json_text);

// The block that parse_sss_extras reads back as the same material (source, model,
// gaussians, scale, albedo mode, thickness, enabled): what the viewer's export writes.
// Every key is written, defaults included, so the file says what it means.
nlohmann::json sss_extras_json(const SssMaterial& material);

// Shared with extras.sss.layers (SssLayers.cpp), whose layers read σa, σs, g and η alike.
namespace detail {
// o[key] as a number (all channels; `scalar` set) or an array of 3 finite numbers; the
// error names "key" or "key[1]".
std::optional<FieldError> read_rgb(const nlohmann::json& o, const char* key, Rgb& out,
                                   bool& scalar);
// A profiles error ("sigma_a[G]", "sigma_t[R]", "eta[0]") named as the user wrote the
// field in `o`: "sigma_a[1]" for an array, "sigma_a" for a single number.
FieldError as_written(FieldError e, const nlohmann::json& o);
// o[key], if present, as a thickness in mm (finite, > 0) into `out` (left as it is when
// absent); the error names `key`.
std::optional<FieldError> read_thickness(const nlohmann::json& o, const char* key, double& out);
}  // namespace detail

}  // namespace sss::scene
