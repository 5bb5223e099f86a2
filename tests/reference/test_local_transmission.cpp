// The diffusion reference's transmission switch (ReferenceOptions::transmission, issue 17's
// transmission link): the three ways light may cross a thin part, each against a closed
// form on a wide flat slab lit from behind, far from its rim, seen from the unlit side.
//
//   profile: the far-side points summed with R(|x_o − x_i|): for an infinite slab of
//            thickness d lit with E, ∫ R(√(ρ² + d²)) 2πρ dρ · E = E ∫_d^∞ 2πs R(s) ds,
//            R's tail beyond d (a slab profile: its T(ρ), whose integral is T_total);
//   local:   the far side dark, each top point given E (−n·l) T(d) / R_d with d ray-cast to
//            the bottom face; blurred by R (mass R_d) that is E T(d): the same tail, now
//            from a local term (a slab profile: T_total / R_d x R_d);
//   off:     the far side dark, nothing added: 0.
// Under a uniform sky of radiance L instead of the light, both faces receive πL, and the
// sky's local term (the surface d behind each point, along −n) makes `local` πL (R_d +
// tail) as `profile` does; `off` keeps πL R_d. The sky's estimate is exact here: each
// cosine-weighted direction of an open hemisphere carries L.
// The tail is integrated here with profiles::integrate_log (geometric panels), not with
// the renderer's RadialSampler cells. Tolerance: the octree at ε = 0.3 reads ~2e-3 of a
// smooth sum (tests/reference/test_octree.cpp, RMS against brute force) and its kernel
// table 1e-3 (ScatterKernel.h); three times their sum is 1%. A wrong thickness (0, or the
// wrong surface) moves the local term by the whole tail ratio (R_d / T(2 mm) > 3 here).
#include "reference/ReferenceRenderer.h"

#include "GroundTruthTestSupport.h"

#include "profiles/Integrate.h"
#include "scene/Environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sss::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr const char* kChannel[3] = {"R", "G", "B"};

// The mean exitant flux M = π · hdr over the 81 pixels, per channel.
Rgb mean_exitance(const scene::Scene& s, Transmission t, Thickness thickness = Thickness::RayCast) {
  ReferenceOptions o;
  o.thickness = thickness;
  o.width = 9;
  o.height = 9;
  o.diffuse_only = true;
  o.transmission = t;  // The default 0.5 mfp spacing: at 1 mfp the far-side sum of the profile switch is off by
  // up to 2.6% (measured), beyond the bound above.
  const ReferenceImage img = render_reference(s, o);
  Rgb m{};
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 9; ++x)
      for (int c = 0; c < 3; ++c) m[c] += kPi * img.hdr.pixel(x, y)[c] / 81.0;
  return m;
}

// R's tail beyond d, ∫_d^S 2πs R(s) ds with s = d + u: smooth from u = 0, geometric panels in u.
double tail_beyond(const profiles::RgbProfile& profile, int c, double d) {
  return profiles::integrate_log(
      [&](double u) { return 2.0 * kPi * (d + u) * profile.channel(c).reflectance(d + u); }, 0.01,
      profile.support_radius() - d, 16);
}

TEST(ReferenceTransmission, SemiInfiniteProfileThroughAThinSlabIsRsTailEitherWay) {
  const double d = 2.0;
  const scene::Scene s = testing::back_lit_slab(profiles::Model::McTable, false, d);
  const profiles::RgbProfile profile = s.materials[0].sss.profile();
  const Rgb profile_m = mean_exitance(s, Transmission::Profile);
  const Rgb local_m = mean_exitance(s, Transmission::Local);
  const Rgb off_m = mean_exitance(s, Transmission::Off);
  for (int c = 0; c < 3; ++c) {
    const double tail = tail_beyond(profile, c, d);
    std::printf("[ %s: R's tail beyond %.1f mm %.5f (R_d %.4f); profile %.5f, local %.5f, off %.2g ]\n", kChannel[c],
                d, tail, profile.total_reflectance()[c], profile_m[c], local_m[c], off_m[c]);
    EXPECT_NEAR(profile_m[c], tail, 0.01 * tail) << kChannel[c];
    EXPECT_NEAR(local_m[c], tail, 0.01 * tail) << kChannel[c];
    EXPECT_EQ(off_m[c], 0.0) << kChannel[c] << ": the far side is dark and nothing is added";
  }
}

TEST(ReferenceTransmission, AUniformSkyCrossesAThinSlabThroughItsInwardThickness) {
  const double d = 2.0, L = 0.5;
  scene::Scene s = testing::back_lit_slab(profiles::Model::McTable, false, d);
  s.lights.clear();
  s.environment = scene::uniform_environment(glm::vec3(float(L)));
  const profiles::RgbProfile profile = s.materials[0].sss.profile();
  const Rgb R_d = profile.total_reflectance();
  // (`profile` and `off` under this sky were checked once, 0.14% and 0.19% from their
  // closed forms at most; they add nothing the light's test does not cover.)
  const Rgb local_m = mean_exitance(s, Transmission::Local);
  // The GPU's thickness: the box's vertex bake, 2 mm at every top vertex (Thickness.h).
  const Rgb baked_m = mean_exitance(s, Transmission::Local, Thickness::ShadowMap);
  for (int c = 0; c < 3; ++c) {
    const double E = kPi * L, tail = tail_beyond(profile, c, d);
    const double both = E * (R_d[c] + tail);
    std::printf("[ %s: sky pi L (R_d + tail) %.5f (pi L R_d alone %.5f); local %.5f, with the baked thickness %.5f ]\n",
                kChannel[c], both, E * R_d[c], local_m[c], baked_m[c]);
    // Without the sky's local term both would be pi L R_d, 1 - R_d / (R_d + tail) = 5-33% low.
    EXPECT_NEAR(local_m[c], both, 0.01 * both) << kChannel[c];
    EXPECT_NEAR(baked_m[c], both, 0.01 * both) << kChannel[c];
  }
}

TEST(ReferenceTransmission, SlabProfileTransmitsItsTotalEitherWay) {
  const double d = 2.0;
  const scene::Scene s = testing::back_lit_slab(profiles::Model::Multipole, true, d);
  const profiles::RgbProfile profile = s.materials[0].sss.profile();
  const Rgb total = profile.total_transmittance();
  const Rgb profile_m = mean_exitance(s, Transmission::Profile);
  const Rgb local_m = mean_exitance(s, Transmission::Local);
  for (int c = 0; c < 3; ++c) {
    std::printf("[ %s: multipole T_total %.5f; profile %.5f, local %.5f ]\n", kChannel[c], total[c], profile_m[c],
                local_m[c]);
    EXPECT_NEAR(profile_m[c], total[c], 0.01 * total[c]) << kChannel[c];
    EXPECT_NEAR(local_m[c], total[c], 0.01 * total[c]) << kChannel[c];
  }
}

TEST(ReferenceTransmission, ProbeRefusesTheRealTimeSwitches) {
  const scene::Scene s = testing::back_lit_slab(profiles::Model::McTable, false, 2.0);
  ReferenceOptions o;
  o.width = 4;
  o.height = 4;
  o.estimator = Estimator::Probe;
  o.spp = 2;
  for (const Transmission t : {Transmission::Local, Transmission::Off}) {
    o.transmission = t;
    try {
      (void)render_reference(s, o);
      ADD_FAILURE() << transmission_name(t) << " was accepted by the probe";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("transmission"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace sss::reference
