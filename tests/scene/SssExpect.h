// One gtest check that two SSS materials are the same: every option and the resolved
// medium, bit for bit (what a written extras.sss block must read back as).
#pragma once

#include "scene/Material.h"

#include <gtest/gtest.h>

#include <string_view>
#include <variant>

namespace sss::scene::testing {

inline void expect_same_sss(const SssMaterial& a, const SssMaterial& b) {
  EXPECT_EQ(a.enabled, b.enabled);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.gaussians, b.gaussians);
  EXPECT_EQ(a.scale, b.scale);
  EXPECT_EQ(a.albedo_mode, b.albedo_mode);
  EXPECT_EQ(a.source.index(), b.source.index());
  EXPECT_EQ(a.medium.sigma_a, b.medium.sigma_a);
  EXPECT_EQ(a.medium.sigma_s, b.medium.sigma_s);
  EXPECT_EQ(a.medium.g, b.medium.g);
  EXPECT_EQ(a.medium.eta, b.medium.eta);
  EXPECT_EQ(a.medium.thickness_mm, b.medium.thickness_mm);
}

// A parser's result (variant<T, FieldError>) for text that must parse, or must not: the
// value or the error, with a test failure naming the text otherwise.
template <class T, class Parse>
T expect_parsed(Parse parse, std::string_view text) {
  auto r = parse(text);
  if (auto* e = std::get_if<FieldError>(&r)) ADD_FAILURE() << text << " -> " << e->what();
  return r.index() == 0 ? std::get<T>(r) : T{};
}

template <class Parse>
FieldError expect_refused(Parse parse, std::string_view text) {
  auto r = parse(text);
  if (r.index() == 0) ADD_FAILURE() << text << " parsed";
  return r.index() == 1 ? std::get<FieldError>(r) : FieldError{};
}

}  // namespace sss::scene::testing
