#include "profiles/Medium.h"
#include "profiles/Presets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace sss::profiles;

namespace {
Medium good() { return Medium::from_reduced({0.032, 0.17, 0.48}, {0.74, 0.88, 1.01}, 1.3); }
std::string field_of(const Medium& m) {
  auto e = m.validate();
  return e ? e->field : std::string("ok");
}
}  // namespace

TEST(Medium, ReducedQuantities) {
  Coefficients c{0.1, 2.0, 0.8, 1.4};
  EXPECT_DOUBLE_EQ(c.sigma_s_reduced(), 0.4);
  EXPECT_DOUBLE_EQ(c.sigma_t_reduced(), 0.5);
  EXPECT_DOUBLE_EQ(c.albedo_reduced(), 0.8);
  EXPECT_DOUBLE_EQ(c.sigma_tr_classical(), std::sqrt(3.0 * 0.1 * 0.5));
  EXPECT_DOUBLE_EQ(c.mfp_reduced(), 2.0);
}

TEST(Medium, ValidMediumPasses) { EXPECT_EQ(field_of(good()), "ok"); }

TEST(Medium, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Medium m = good();
  m.sigma_a[1] = -0.1;
  EXPECT_EQ(field_of(m), "sigma_a[G]");
  m = good(); m.sigma_a[2] = nan;
  EXPECT_EQ(field_of(m), "sigma_a[B]");
  m = good(); m.sigma_s[0] = -1.0;
  EXPECT_EQ(field_of(m), "sigma_s[R]");
  m = good(); m.sigma_s[0] = inf;
  EXPECT_EQ(field_of(m), "sigma_s[R]");
  m = good(); m.sigma_a[0] = 0.0;  // albedo of 1
  EXPECT_EQ(field_of(m), "sigma_a[R]");
  m = good(); m.sigma_a[0] = 0.0; m.sigma_s[0] = 0.0;  // σt = 0
  EXPECT_EQ(field_of(m), "sigma_t[R]");
  m = good(); m.g[1] = 1.0;
  EXPECT_EQ(field_of(m), "g[G]");
  m = good(); m.g[1] = -1.2;
  EXPECT_EQ(field_of(m), "g[G]");
  m = good(); m.eta[2] = 0.0;
  EXPECT_EQ(field_of(m), "eta[B]");
  m = good(); m.thickness_mm = 0.0;
  EXPECT_EQ(field_of(m), "thickness");
  m = good(); m.thickness_mm = nan;
  EXPECT_EQ(field_of(m), "thickness");
}

TEST(Medium, MessagesSayWhatIsWrong) {
  Medium m = good();
  m.sigma_a[0] = 0.0;
  EXPECT_NE(m.validate()->message.find("albedo of 1"), std::string::npos);
}

TEST(Presets, AllTwelveJensenMedia) {
  EXPECT_EQ(presets().size(), 12u);
  for (const char* n : {"apple", "chicken1", "chicken2", "cream", "ketchup", "marble", "potato",
                        "skimmilk", "skin1", "skin2", "spectralon", "wholemilk"})
    EXPECT_NE(find_preset(n), nullptr) << n;
  EXPECT_EQ(find_preset("jade"), nullptr);
  EXPECT_EQ(find_preset("marble")->eta, 1.5);
  EXPECT_EQ(find_preset("skin1")->eta, 1.3);
}

TEST(Presets, SpectralonIsRejectedBecauseItDoesNotAbsorb) {
  // Jensen's table lists σa = 0.00 for spectralon: an albedo of 1, which has no finite
  // diffusion length. It is listed but refused with the field named.
  auto e = preset_medium(*find_preset("spectralon")).validate();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->field, "sigma_a[R]");
}
