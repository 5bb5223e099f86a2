// The SSS block of a glTF material: materials[i].extras.sss (DESIGN.md §3).
//
//   {"preset": "skin1"}
//   {"sigma_a": [r,g,b], "sigma_s": [r,g,b], "g": g, "eta": e}      (mm^-1)
//   {"color": [r,g,b], "mfp": [r,g,b]}                 (reduced mean free path, mm)
// plus, with any of them: "model" (dipole | better-dipole | pbd | burley | multipole |
// mc | mc-table, default profiles::kDefaultModel = mc-table), "gaussians" (1..8, default 6), "scale" (> 0, default 1),
// "albedo_mode" ("post-scatter" | "pre-post"), "thickness" (mm, default infinite),
// "enabled" (default true). σa, σs, g, η, colour and mfp take a number (all channels)
// or an array of 3. With a colour, g and η must be single numbers.
//
// Errors name the field inside the block as the user wrote it: "sigma_a[1]" for the
// second array element, "g" for a single number, "foo" for an unknown key.
#pragma once

#include "renderer/scene/Material.h"

#include <nlohmann/json_fwd.hpp>

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

}  // namespace sss::scene
