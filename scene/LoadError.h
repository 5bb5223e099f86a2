// LoadError: why a scene could not be loaded, as a value (DESIGN.md §8). It names the
// file, the object inside it ("accessors[3]", "materials[2]") and the field
// ("byteOffset", "extras.sss.sigma_a[1]"), so a user can find the line to fix.
#pragma once

#include <string>

namespace sss::scene {

struct LoadError {
  std::string file;     // the path as given, or "builtin:NAME"
  std::string object;   // "accessors[3]"; empty for the file as a whole
  std::string field;    // "byteOffset"; empty when the whole object is at fault
  std::string message;  // what is wrong and, where it helps, what was expected

  // "file.gltf: materials[2].extras.sss.sigma_a[1]: must be >= 0 mm^-1, got -1"
  std::string what() const;
};

}  // namespace sss::scene
