#include "profiles/ArtistMapping.h"
#include "profiles/Presets.h"

#include "MediumExpect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <variant>

using namespace sss::profiles;

namespace {
using sss::profiles::testing::ok;
}  // namespace

TEST(ArtistMapping, RoundTripEveryAnalyticModel) {
  // colour + mfp → medium → the model's total reflectance must give the colour back.
  // Bisection in √(1-α') runs to 1e-15, so the round trip is limited by the model's
  // total: closed forms to ~1e-12, PBD's numerical total (fixed quadrature, the same
  // function both ways) likewise. Tolerance 1e-9.
  const ArtistParameters p{{0.8, 0.45, 0.2}, {1.2, 0.6, 0.3}, 1.4, 0.0};
  for (Model m : {Model::Dipole, Model::BetterDipole, Model::Pbd, Model::Burley}) {
    const Medium med = ok(medium_from_artist(m, p));
    const RgbProfile prof(m, med);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(prof.total_reflectance()[c], p.color[c], 1e-9) << model_name(m) << c;
      EXPECT_NEAR(med.channel(c).mfp_reduced(), p.mfp_mm[c], 1e-12);
    }
  }
}

TEST(ArtistMapping, RoundTripThroughAPresetAndBack) {
  // skin1 → its dipole colour and mfp → coefficients equal to the preset's.
  const Medium skin = preset_medium(*find_preset("skin1"));
  const RgbProfile prof(Model::Dipole, skin);
  ArtistParameters p;
  p.eta = 1.3;
  for (int c = 0; c < 3; ++c) {
    p.color[c] = prof.total_reflectance()[c];
    p.mfp_mm[c] = skin.channel(c).mfp_reduced();
  }
  const Medium back = ok(medium_from_artist(Model::Dipole, p));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(back.sigma_a[c], skin.sigma_a[c], 1e-9 * skin.channel(c).sigma_t_reduced());
    EXPECT_NEAR(back.sigma_s[c], skin.sigma_s[c], 1e-9 * skin.channel(c).sigma_t_reduced());
  }
}

TEST(ArtistMapping, ThinSlabUsesTheMultipoleTotal) {
  ArtistParameters p{{0.3, 0.3, 0.3}, {1.0, 1.0, 1.0}, 1.3, 0.0, 2.0};
  const Medium med = ok(medium_from_artist(Model::Multipole, p));
  const RgbProfile prof(Model::Multipole, med);
  EXPECT_NEAR(prof.total_reflectance()[0], 0.3, 1e-9);
}

TEST(ArtistMapping, RejectsWhatCannotBeInverted) {
  auto field = [](const ArtistParameters& p, Model m = Model::BetterDipole) {
    auto v = medium_from_artist(m, p);
    return std::holds_alternative<sss::FieldError>(v) ? std::get<sss::FieldError>(v).field
                                                       : std::string("ok");
  };
  ArtistParameters p{{0.5, 0.5, 0.5}, {1, 1, 1}};
  EXPECT_EQ(field(p), "ok");
  p.color[1] = 1.0;  // an albedo of 1
  EXPECT_EQ(field(p), "color[G]");
  p.color[1] = 0.0;
  EXPECT_EQ(field(p), "color[G]");
  p.color[1] = std::nan("");
  EXPECT_EQ(field(p), "color[G]");
  p = {{0.5, 0.5, 0.5}, {1, -1, 1}};
  EXPECT_EQ(field(p), "mfp[G]");
  p = {{0.5, 0.5, 0.5}, {1, 1, 1}, 1.3, 1.0};
  EXPECT_EQ(field(p), "g");
  p = {{0.5, 0.5, 0.5}, {1, 1, 1}};
  EXPECT_EQ(field(p, Model::MonteCarlo), "model[R]");
  // A thin slab cannot reflect 0.99: with d = 1.5 mfp the multipole's limit for α' → 1 is
  // (d + z_b - ℓ)/(d + 2 z_b) ≈ 0.45.
  p = {{0.99, 0.5, 0.5}, {1, 1, 1}, 1.3, 0.0, 1.5};
  EXPECT_EQ(field(p, Model::Multipole), "color[R]");
  // Thinner than one reduced mean free path: the multipole does not apply.
  p = {{0.3, 0.3, 0.3}, {1, 1, 1}, 1.3, 0.0, 0.5};
  EXPECT_EQ(field(p, Model::Multipole), "thickness[R]");
}
