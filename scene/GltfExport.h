// GltfExport: a copy of a glTF or GLB file with its materials' extras.sss rewritten from
// edited materials (the viewer's "export material"). Only the JSON changes: a GLB keeps
// its BIN chunk byte for byte, external buffers and images are referenced as before.
// This module makes the bytes; the caller writes them (image::write_file_atomically),
// so that a failure leaves nothing half-written.
#pragma once

#include "scene/LoadError.h"
#include "scene/Material.h"

#include <string>
#include <variant>
#include <vector>

namespace sss::scene {

// The file at `input` (as loaded by load_scene) with materials[i].extras.sss replaced by
// sss_extras_json(materials[i].sss) for each i below the file's material count whose
// material has SSS enabled or had an extras.sss block (other extras keys are kept;
// materials past the file's count, such as the loader's default material, are not in
// the file and are skipped). `output` is where the bytes will go: it must not be
// `input` itself (never overwrite the source), and when the file refers to external
// files by relative URI it must lie in the same folder, since those URIs are relative
// to it and the loader accepts no "..". Each enabled single-medium material also gets
// the KHR material extensions of khr_extensions_json (KhrMaterials.h; lengths in scene
// units, `mm_per_unit` mm each: glTF's metres by default), listed in extensionsUsed and
// never in extensionsRequired. Errors name the file and the field.
std::variant<std::string, LoadError> gltf_with_sss_materials(const std::string& input,
                                                             const std::vector<Material>& materials,
                                                             const std::string& output,
                                                             double mm_per_unit = 1000.0);

// A path that does not exist yet: `wanted` if it is free, else "stem-2.ext",
// "stem-3.ext", ... in the same folder.
std::string unused_path(const std::string& wanted);

// The default export name for `input`: "folder/stem-sss.ext", made unused.
std::string default_export_path(const std::string& input);

}  // namespace sss::scene
