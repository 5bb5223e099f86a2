// A profiles result that must be a medium: the medium, or a test failure with the error.
#pragma once

#include "profiles/Medium.h"

#include <gtest/gtest.h>

#include <variant>

namespace sss::profiles::testing {

inline Medium ok(const std::variant<Medium, sss::FieldError>& v) {
  if (auto* e = std::get_if<sss::FieldError>(&v)) {
    ADD_FAILURE() << e->what();
    return {};
  }
  return std::get<Medium>(v);
}

}  // namespace sss::profiles::testing
