#include "scene/LoadError.h"

namespace sss::scene {

std::string LoadError::what() const {
  std::string location = object;
  if (!field.empty()) {
    if (!location.empty() && field.front() != '[') location += '.';
    location += field;
  }
  std::string s = file.empty() ? std::string("<scene>") : file;
  if (!location.empty()) s += ": " + location;
  return s + ": " + message;
}

}  // namespace sss::scene
