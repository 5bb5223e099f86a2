// A stack of layers (issue 19, profiles/Layered.h), as glTF's materials[i].extras.sss.layers
// and as `sss-fit --layers FILE.json` give it. Top first; each entry is one layer:
//
//   {"sigma_a": [r,g,b], "sigma_s": [r,g,b], "g": g, "eta": e, "thickness_mm": d}  (mm^-1, mm)
//   {"preset": "skin1", "thickness_mm": d}
//
// σa, σs, g and η take a number (all channels) or an array of 3, as in extras.sss
// (SssExtras.h): sigma_a and sigma_s are required, g defaults to 0 and η to 1.3. A preset
// layer takes the preset's coefficients and its η (profiles/Presets.h) and nothing else.
// thickness_mm (> 0, finite) is required on every layer but the last; the last may leave
// it out and is then a semi-infinite base.
//
// Every layer of a stack has the same η (the interfaces between layers are index-matched,
// profiles/Layered.h): a layer whose η (given, defaulted to 1.3, or its preset's) differs
// from the top layer's is an error. Every preset has η = 1.3 but marble (1.5).
//
// Errors name the field as the user wrote it, from the array: "layers" (not an array,
// empty, more than profiles::kMaxLayers entries), "layers[1]" (not an object, neither or
// both of preset and sigma_a + sigma_s), "layers[1].sigma_a[2]" (an array element),
// "layers[1].g" (a single number), "layers[0].thickness_mm", "layers[2].preset" (unknown
// preset, or a preset whose η differs), "layers[0].foo" (an unknown key).
#pragma once

#include "profiles/Layered.h"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <string_view>
#include <variant>

namespace sss::scene {

// The array itself (the value of "layers"). The stack has passed profiles::validate_layers.
std::variant<profiles::LayerStack, FieldError> parse_sss_layers(const nlohmann::json& layers);

// A file holding {"layers": [...]} and nothing else (`sss-fit --layers`). An error about
// the file itself (missing, unreadable, not JSON, nested too deep) has the path as its
// field, and a malformed file's message says where (nlohmann's line and column); an
// error inside the document names the field as parse_sss_layers does ("layers",
// "layers[1].sigma_a[2]"), or the unknown top-level key.
std::variant<profiles::LayerStack, FieldError> parse_sss_layers_file(const std::string& path);

// The same from JSON text ({"layers": [...]}): the file's contents, for tests and fuzzing.
// Errors about the text itself (not JSON, too deep) have an empty field.
std::variant<profiles::LayerStack, FieldError> parse_sss_layers_text(std::string_view json_text);

}  // namespace sss::scene
