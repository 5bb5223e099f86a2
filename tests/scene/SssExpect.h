// One gtest check that two SSS materials are the same: every option and the resolved
// medium, bit for bit (what a written extras.sss block must read back as).
#pragma once

#include "renderer/scene/Material.h"

#include <gtest/gtest.h>

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

}  // namespace sss::scene::testing
