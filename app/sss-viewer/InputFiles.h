// The viewer never overwrites a user's input file (issue 7): the files a loaded scene
// came from (the glTF/GLB and every buffer and image it names by relative URI) are
// listed once per scene, and every output (--out, --screenshot, the Screenshot panel,
// the Tools window's exports, --atlas-out, --soak-csv/--soak-svg) is checked against
// them with std::filesystem::equivalent (the same file by any name: another relative
// path, a symlink, a hard link).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sss::app {

// The scene file and the external files it names; empty for builtin:NAME. The scene has
// loaded, so its URIs passed the loader's checks (relative, below its folder); a file
// that cannot be read again yields just the scene file itself.
std::vector<std::filesystem::path> scene_input_files(const std::string& source);

// Why `output` must not be written (it is one of `inputs`), or nullopt.
std::optional<std::string> refuse_input_overwrite(const std::string& output,
                                                  const std::vector<std::filesystem::path>& inputs);

}  // namespace sss::app
